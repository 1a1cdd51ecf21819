"""Sweeps on a TLS dask cluster on localhost (a private certificate authority made here, a
`dask scheduler` and a `dask worker` started with its certificates), and every address or
certificate mistake failing as one ClusterError line before any simulation, leaving nothing
behind.

One scheduler (with its dashboard), one worker and one plain HTTP server serve the whole module:
starting processes is most of the time these tests take."""
from __future__ import annotations

import argparse
import datetime
import http.server
import ipaddress
import re
import shutil
import subprocess
import sys
import threading
from functools import partial
from pathlib import Path

import dask
import numpy as np
import pytest

import pipeline
from pipeline.cluster import add_tls_options, apply_tls_options
from pipeline.errors import ClusterError
from pipeline.histories import segment
from pipeline.records import load_record
from tests.pipeline.small_sweep import no_compute
from tests.pipeline.test_cluster import (
    ENV,
    GRID,
    _free_port,
    _scheduler,
    _stop,
    _wait_for_port,
    _wait_for_workers,
    _worker,
)

TLS_KEYS = ("distributed.comm.tls.ca-file", "distributed.comm.tls.client.cert",
            "distributed.comm.tls.client.key")


# --- a private certificate authority ------------------------------------------------------

def _pki(folder: Path) -> dict[str, str]:
    """Two certificate authorities, each with a certificate and key for localhost and
    127.0.0.1: ca, cert, key (the cluster's and this client's) and other_ca, other_cert,
    other_key (another authority's). With the cryptography package, else openssl."""
    try:
        import cryptography  # noqa: F401

        make = _signed_by_cryptography
    except ImportError:
        if shutil.which("openssl") is None:
            pytest.skip("neither the cryptography package nor openssl to make certificates")
        make = _signed_by_openssl
    files = {}
    for prefix in ("", "other_"):
        for name, path in make(folder, prefix + "authority").items():
            files[prefix + name] = str(path)
    return files


def _signed_by_cryptography(folder: Path, name: str) -> dict[str, Path]:
    from cryptography import x509
    from cryptography.hazmat.primitives import hashes, serialization
    from cryptography.hazmat.primitives.asymmetric import ec
    from cryptography.x509.oid import NameOID

    now = datetime.datetime.now(datetime.timezone.utc)

    def certificate(subject, issuer, public_key, signing_key, extension):
        return (x509.CertificateBuilder().subject_name(subject).issuer_name(issuer)
                .public_key(public_key).serial_number(x509.random_serial_number())
                .not_valid_before(now - datetime.timedelta(hours=1))
                .not_valid_after(now + datetime.timedelta(days=1))
                .add_extension(extension, critical=isinstance(extension, x509.BasicConstraints))
                .sign(signing_key, hashes.SHA256()))

    ca_key, key = ec.generate_private_key(ec.SECP256R1()), ec.generate_private_key(ec.SECP256R1())
    ca_name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, name)])
    ca = certificate(ca_name, ca_name, ca_key.public_key(), ca_key,
                     x509.BasicConstraints(ca=True, path_length=None))
    leaf = certificate(x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "localhost")]),
                       ca_name, key.public_key(), ca_key,
                       x509.SubjectAlternativeName([
                           x509.DNSName("localhost"),
                           x509.IPAddress(ipaddress.ip_address("127.0.0.1"))]))
    paths = {part: folder / f"{name}-{part}.pem" for part in ("ca", "cert", "key")}
    paths["ca"].write_bytes(ca.public_bytes(serialization.Encoding.PEM))
    paths["cert"].write_bytes(leaf.public_bytes(serialization.Encoding.PEM))
    paths["key"].write_bytes(key.private_bytes(serialization.Encoding.PEM,
                                               serialization.PrivateFormat.PKCS8,
                                               serialization.NoEncryption()))
    return paths


def _signed_by_openssl(folder: Path, name: str) -> dict[str, Path]:
    paths = {part: folder / f"{name}-{part}.pem" for part in ("ca", "cert", "key")}
    ca_key, request, extensions = (folder / f"{name}-{part}" for part in
                                   ("ca-key.pem", "request.csr", "extensions.cnf"))
    extensions.write_text("subjectAltName=DNS:localhost,IP:127.0.0.1\n")
    ec = ["-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes"]
    for argv in (["req", "-x509", *ec, "-keyout", ca_key, "-out", paths["ca"], "-days", "1",
                  "-subj", f"/CN={name}"],
                 ["req", *ec, "-keyout", paths["key"], "-out", request, "-subj", "/CN=localhost"],
                 ["x509", "-req", "-in", request, "-CA", paths["ca"], "-CAkey", ca_key,
                  "-CAcreateserial", "-out", paths["cert"], "-days", "1", "-extfile",
                  extensions]):
        subprocess.run(["openssl", *map(str, argv)], check=True, capture_output=True)
    return paths


# --- fixtures: shared by the module, always stopped -----------------------------------------

@pytest.fixture(scope="module")
def pki(tmp_path_factory) -> dict[str, str]:
    return _pki(tmp_path_factory.mktemp("pki"))


@pytest.fixture(scope="module")
def tls_cluster(tmp_path_factory, pki):
    """(address, dashboard port) of a TLS scheduler with one worker (no nanny: one process
    fewer to start); scheduler and worker start together (the worker retries until the
    scheduler listens)."""
    from distributed import Security

    tmp = tmp_path_factory.mktemp("tls_cluster")
    files = ("--tls-ca-file", pki["ca"], "--tls-cert", pki["cert"], "--tls-key", pki["key"])
    dashboard = _free_port()
    scheduler, address = _scheduler(tmp, *files, "--dashboard-address",
                                    f"127.0.0.1:{dashboard}", scheme="tls", wait=False)
    worker = None
    try:
        worker = _worker(tmp, address, nanny=False, options=files)
        _wait_for_port(int(address.rsplit(":", 1)[1]), scheduler)
        _wait_for_port(dashboard, scheduler)
        _wait_for_workers(address, 1, Security(tls_ca_file=pki["ca"], tls_client_cert=pki["cert"],
                                               tls_client_key=pki["key"],
                                               require_encryption=True))
        yield address, dashboard
    finally:
        _stop(*[proc for proc in (worker, scheduler) if proc is not None])


@pytest.fixture(scope="module")
def http_port(tmp_path_factory):
    """The port of a plain HTTP server (python -m http.server's, in a thread of this
    process)."""
    handler = partial(_QuietHandler, directory=str(tmp_path_factory.mktemp("www")))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield server.server_address[1]
    finally:
        server.shutdown()
        server.server_close()


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):  # no request lines in the test output
        pass


@pytest.fixture
def tls_config(pki):
    """The cluster's certificates in dask's configuration, as a user would set them."""
    with dask.config.set(dict(zip(TLS_KEYS, (pki["ca"], pki["cert"], pki["key"]),
                                  strict=True))):
        yield


@pytest.fixture(scope="module")
def record():
    return segment(load_record("pacoima"), 12.0)


# --- runs ----------------------------------------------------------------------------------

def _assert_same(here, there) -> None:
    for name in here.data_vars:
        np.testing.assert_array_equal(here[name].values, there[name].values, err_msg=name)


def test_tls_run_equals_local_run(tls_cluster, tls_config, record):
    """tls://: the certificates from dask's configuration; the numbers of a local run."""
    address, _ = tls_cluster
    here = pipeline.sweep([record], workers=1, **GRID)
    there = pipeline.sweep([record], scheduler=address, batch_size=3, **GRID)
    _assert_same(here, there)


def test_users_client_with_its_own_security(tls_cluster, pki, record):
    """A Client the user built with a Security of their own (nothing in dask's configuration)
    is used as it is."""
    from distributed import Client, Security

    security = Security(tls_ca_file=pki["ca"], tls_client_cert=pki["cert"],
                        tls_client_key=pki["key"], require_encryption=True)
    grid = {"gap": [0.15, 0.2], "quiet": True}
    with dask.config.set(dict.fromkeys(TLS_KEYS)), \
            Client(tls_cluster[0], security=security, set_as_default=False) as client:
        there = pipeline.sweep([record], scheduler=client, **grid)
    _assert_same(pipeline.sweep([record], **grid), there)


# --- refusals ------------------------------------------------------------------------------

# (id, address from (tls address, dashboard port, http port), certificates from the pki
# (None: none configured), what the message says)
REFUSALS = [
    ("dashboard-url", lambda tls, dash, web: f"http://127.0.0.1:{dash}", None,
     r"is a web address \(the dashboard's, port 8787 by default\), not a scheduler's: give "
     r"tcp://127\.0\.0\.1:8786"),
    ("unknown-scheme", lambda tls, dash, web: "ftp://127.0.0.1:8786", None,
     r"scheme 'ftp' is not taken here; a scheduler's address is tcp://HOST:PORT \(port 8786 "
     r"by default\) or tls://HOST:PORT"),
    ("other-dask-transport", lambda tls, dash, web: "ucx://127.0.0.1:8786", None,
     r"scheme 'ucx' is not taken here; .*for dask's other transports, .*ucx://.*: pass a "
     r"distributed\.Client of your own as scheduler="),
    ("no-port", lambda tls, dash, web: "tcp://127.0.0.1", None,
     r"not an address of the form tcp://HOST:PORT \(missing port"),
    ("bad-port", lambda tls, dash, web: "tls://127.0.0.1:scheduler", None,
     r"not an address of the form tls://HOST:PORT"),
    ("nothing-listening", lambda tls, dash, web: f"tcp://127.0.0.1:{_free_port()}", None,
     r"nothing listens there \(connection refused\)"),
    ("dashboard-port", lambda tls, dash, web: f"tcp://127.0.0.1:{dash}", None,
     r"is a web server \(it answers HTTP\), not a dask scheduler: the dashboard listens on "
     r"port 8787 by default"),
    ("http-server", lambda tls, dash, web: f"tcp://127.0.0.1:{web}", None,
     r"is a web server \(it answers HTTP\)"),
    ("tcp-to-tls-scheduler", lambda tls, dash, web: tls.replace("tls://", "tcp://"), None,
     r"speaks TLS: give tls://127\.0\.0\.1:\d+ instead, with certificates \(--tls-ca-file"),
    ("tls-without-certificates", lambda tls, dash, web: tls, None,
     r"needs TLS certificates, and distributed\.comm\.tls\.ca-file and "
     r"distributed\.comm\.tls\.client\.cert are not set: give --tls-ca-file"),
    ("tls-to-plain-server", lambda tls, dash, web: f"tls://127.0.0.1:{web}",
     ("ca", "cert", "key"), r"the server there does not speak TLS"),
    ("certificate-of-another-authority", lambda tls, dash, web: tls,
     ("ca", "other_cert", "other_key"),
     r"refused this client's certificate .*other_authority-cert\.pem \(.*alert.*\): it must "
     r"be signed by the certificate authority the scheduler trusts"),
    ("scheduler-not-trusted", lambda tls, dash, web: tls, ("other_ca", "cert", "key"),
     r"its certificate is not signed by the authority in .*other_authority-ca\.pem"),
    ("missing-key", lambda tls, dash, web: tls, ("ca", "cert", "missing"),
     r"dask's configuration distributed\.comm\.tls\.client\.key = .*missing\.pem: cannot read "
     r"it \(No such file or directory\)"),
]


@pytest.mark.parametrize("address, certificates, message",
                         [case[1:] for case in REFUSALS], ids=[case[0] for case in REFUSALS])
def test_refused_in_one_line(address, certificates, message, tls_cluster, http_port, pki,
                             record, tmp_path, capfd, monkeypatch):
    """Each address or certificate mistake: one ClusterError line naming it, before any
    simulation and before anything is written, and nothing on stderr. Refused before any dask
    Client exists: one that fails to start prints tracebacks when collected, at exit."""
    files = {**pki, "missing": str(tmp_path / "missing.pem")}
    settings = dict(zip(TLS_KEYS, [files[name] for name in certificates] if certificates
                        else [None] * 3, strict=True))
    out = tmp_path / "run" / "x.nc"
    out.parent.mkdir()
    monkeypatch.setattr("distributed.Client", _no_client)
    no_compute(monkeypatch)
    with dask.config.set(settings), pytest.raises(ClusterError, match=message) as caught:
        pipeline.sweep([record], gap=0.2, quiet=True, out=out,
                       scheduler=address(tls_cluster[0], tls_cluster[1], http_port))
    assert "\n" not in str(caught.value)
    assert not list(out.parent.iterdir()), "the refused run left files behind"
    assert capfd.readouterr().err == ""


def _no_client(*args, **kwargs):
    raise AssertionError("a dask Client was made for an address that is refused")


def test_encryption_required(record, tmp_path):
    """dask's configuration requiring encryption refuses a tcp:// address before connecting."""
    with dask.config.set({"distributed.comm.require-encryption": True}), \
            pytest.raises(ClusterError, match=r"requires encryption \(distributed\.comm\."
                                              r"require-encryption\): give its tls:// address"):
        pipeline.sweep([record], gap=0.2, quiet=True, scheduler=f"tcp://127.0.0.1:{_free_port()}")


def test_refused_zarr_run_leaves_nothing(record, tmp_path):
    """A Zarr run writes its template before connecting: refused, it removes it."""
    with pytest.raises(ClusterError, match="is a web address"):
        pipeline.sweep([record], gap=0.2, quiet=True, out=tmp_path / "x.zarr",
                       scheduler="http://127.0.0.1:8787")
    assert not list(tmp_path.iterdir()), "the refused run left files behind"


def test_tls_options(pki, tmp_path):
    """--tls-*: said in --help, put into dask's configuration as absolute paths, a file that
    cannot be read refused naming its option."""
    parser = argparse.ArgumentParser()
    add_tls_options(parser)
    shown = " ".join(parser.format_help().split())
    for key in TLS_KEYS:
        assert key in shown
    with dask.config.set(dict.fromkeys(TLS_KEYS)):  # restores what apply_tls_options sets
        apply_tls_options(parser.parse_args(["--tls-ca-file", pki["ca"], "--tls-cert",
                                             pki["cert"], "--tls-key", pki["key"]]))
        assert [dask.config.get(key) for key in TLS_KEYS] == \
            [str(Path(pki[name]).absolute()) for name in ("ca", "cert", "key")]
        missing = tmp_path / "key.pem"
        with pytest.raises(ClusterError, match=re.escape(f"--tls-key {missing}: cannot read")):
            apply_tls_options(parser.parse_args(["--tls-cert", pki["cert"],
                                                 "--tls-key", str(missing)]))


def test_command_line_dashboard_address(tmp_path):
    """The common slip on the command line: exit status 2, one line, no output written
    (the timeout only guards against a hang)."""
    done = subprocess.run([sys.executable, "-m", "studies.sweep", "--records", "kobe",
                           "--gap-cm", "30", "--scheduler", "http://127.0.0.1:8787",
                           "--out", str(tmp_path / "out")],
                          cwd=tmp_path, env=ENV, capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 2, done.stderr
    assert len(done.stderr.splitlines()) == 1, done.stderr
    assert "is a web address (the dashboard's" in done.stderr
    assert not (tmp_path / "out").exists()
