"""Connecting to a dask.distributed cluster, and refusing one that cannot run a sweep.

A sweep submitted to a cluster whose workers cannot import the project, or run another
version of it, fails far from its cause (dask reports a cancelled future; the real error is in
a worker's log) or, worse, mixes results of two engines. So before any batch is submitted the
client checks, each failure being one ClusterError line that names the cause and the fix:
the address is a scheduler's (check_address), a dask scheduler answers there (probe, within
CONNECT_TIMEOUT), it has workers (WORKERS_TIMEOUT), every worker can import the project, and
every worker's engine fingerprint (pipeline.provenance) equals this process's. A worker that
dies during the run needs nothing from here: the scheduler gives its batches to the others
(results do not depend on where a batch runs).

Why a probe of our own before dask's Client: dask's connection handshake has no timeout (an
HTTP server, such as the dashboard, leaves the Client waiting for ever) and a Client that fails
to start prints tracebacks from its finaliser. The probe speaks plain sockets: a dask scheduler
greets first, unprompted; a web server answers an HTTP request; a TLS server answers a TLS
handshake. It then completes dask's handshake with the scheduler's own greeting, so that the
scheduler logs nothing. Addresses are tcp:// or tls://, the transports the probe knows; for
dask's others, the caller passes a Client of its own, used as it is.

TLS (tls://HOST:PORT): the certificates come from dask's configuration
(distributed.comm.tls.ca-file, distributed.comm.tls.client.cert, distributed.comm.tls.client.key,
read by distributed.Security) or, on the command line, from --tls-ca-file, --tls-cert and
--tls-key (add_tls_options, apply_tls_options), which set that configuration.
"""
from __future__ import annotations

import socket
import ssl
import struct
import time
from contextlib import contextmanager
from pathlib import Path

from .errors import ClusterError

CONNECT_TIMEOUT = 5.0  # s: the probe (connection, TLS handshake, first answer), then the Client
GREETING_WAIT = 1.0  # s: a dask scheduler greets at once; a server silent this long is asked HTTP
WORKERS_TIMEOUT = 10.0  # s
SCHEDULER_PORT, DASHBOARD_PORT = 8786, 8787  # dask's defaults
# Address schemes taken: those the probe knows. A Client of dask's other transports (inproc,
# ucx, ws...) fails inside its constructor, where dask prints tracebacks; such a Client the user
# builds and passes as the scheduler is used as it is (pipeline.execute.dask_client).
SCHEMES = ("tcp", "tls")
HTTP_REQUEST = b"HEAD / HTTP/1.0\r\n\r\n"
MAX_GREETING = 1 << 20  # bytes: a dask greeting is ~60; anything announcing more is not one
START_HINT = ("start a scheduler with `dask scheduler` and workers with `dask worker "
              "tcp://HOST:8786 --nthreads 1` (see docs/clusters.md)")
# The command-line options, the dask configuration keys they set, and the attributes of
# distributed.Security holding them.
TLS_SETTINGS = (("--tls-ca-file", "distributed.comm.tls.ca-file", "tls_ca_file"),
                ("--tls-cert", "distributed.comm.tls.client.cert", "tls_client_cert"),
                ("--tls-key", "distributed.comm.tls.client.key", "tls_client_key"))
TLS_HINT = ("--tls-ca-file, --tls-cert and --tls-key on the command line, or "
            + ", ".join(key for _, key, _ in TLS_SETTINGS) + " in dask's configuration")
# Expressions evaluated on the workers with the builtin eval: a builtin is found by name on
# any worker, whereas a function of this project cannot even be unpickled on a worker that
# lacks the project, which is the case to detect.
CAN_IMPORT = "__import__('importlib.util').util.find_spec('engine') is not None " \
             "and __import__('importlib.util').util.find_spec('pipeline') is not None"
FINGERPRINT = "__import__('pipeline.provenance').provenance.engine_fingerprint()"


def add_tls_options(parser) -> None:
    """--tls-ca-file, --tls-cert, --tls-key: the certificates for a tls:// scheduler (then
    apply_tls_options(args))."""
    group = parser.add_argument_group(
        "TLS", "certificates (PEM files) for a --scheduler tls://HOST:PORT; dask's "
               "configuration (distributed.comm.tls.*) is the alternative to these options")
    group.add_argument("--tls-ca-file", metavar="FILE",
                       help="the certificate authority that signed the scheduler's "
                            "certificate (default: dask's configuration "
                            "distributed.comm.tls.ca-file)")
    group.add_argument("--tls-cert", metavar="FILE",
                       help="this client's certificate, signed by an authority the scheduler "
                            "trusts (default: dask's configuration "
                            "distributed.comm.tls.client.cert)")
    group.add_argument("--tls-key", metavar="FILE",
                       help="the private key of --tls-cert, unless that file holds it "
                            "(default: dask's configuration distributed.comm.tls.client.key)")


def apply_tls_options(args) -> None:
    """Put the --tls-* files given in `args` into dask's configuration for this process (the
    Client reads them from there); ClusterError naming the option for a file it cannot read."""
    import dask

    given = {}
    for option, key, _ in TLS_SETTINGS:
        value = getattr(args, option[2:].replace("-", "_"), None)
        if value is not None:
            path = Path(value).expanduser().absolute()
            given[key] = str(check_readable(path, option))
    if given:
        dask.config.set(given)  # not as a context manager: for the rest of the process


def check_readable(path, name: str) -> Path:
    """`path` if it is a file this process can read, else ClusterError naming `name`."""
    try:
        with open(path, "rb"):
            pass
    except OSError as err:
        raise ClusterError(f"{name} {path}: cannot read it ({err.strerror or err})") from None
    return Path(path)


@contextmanager
def connect(address: str):
    """A checked Client of the scheduler at `address` (closed on exit)."""
    security = client_security(address)
    probe(address, security)
    with _client(address, security) as client:
        check_workers(client)
        yield client


def client_security(address: str):
    """The distributed.Security the Client would use: a configured security loader's
    (distributed.client.security-loader), else dask's configuration (Security())."""
    import dask
    from distributed import Security

    loader = dask.config.get("distributed.client.security-loader", None)
    security = None
    if loader:
        from distributed.utils import import_term

        security = import_term(loader)({"address": address})
    return security if security is not None else Security()


def _client(address: str, security):
    """dask's Client of the (probed) scheduler at `address`, or ClusterError."""
    from distributed import Client

    try:
        return Client(address, security=security, timeout=CONNECT_TIMEOUT,
                      set_as_default=False)
    except Exception as err:  # whatever dask raises becomes the one line the user reads
        raise ClusterError(f"scheduler {address}: no connection within {CONNECT_TIMEOUT:g} s "
                           f"({type(err).__name__}: {_one_line(err)}); check the address, or "
                           f"{START_HINT}") from None


def check_address(address: str) -> tuple[str, str, int]:
    """(scheme, host, port) of a scheduler address; ClusterError for a web address, another
    scheme than tcp and tls, or a malformed address."""
    from distributed.comm import registry
    from distributed.comm.addressing import parse_address, parse_host_port

    scheme, location = parse_address(address, strict=False)  # no scheme: tcp, as dask
    if scheme in ("http", "https"):
        raise ClusterError(_web_address(address))
    if scheme not in SCHEMES:
        others = ", ".join(f"{s}://" for s in sorted(set(registry.backends) - set(SCHEMES)))
        raise ClusterError(f"scheduler {address}: scheme {scheme!r} is not taken here; a "
                           f"scheduler's address is tcp://HOST:PORT (port {SCHEDULER_PORT} by "
                           f"default) or tls://HOST:PORT (for dask's other transports, "
                           f"{others}: pass a distributed.Client of your own as scheduler=)")
    try:
        host, port = parse_host_port(location)
        port = int(port)
    except (ValueError, TypeError) as err:
        raise ClusterError(f"scheduler {address}: not an address of the form "
                           f"{scheme}://HOST:PORT ({err}); a scheduler listens on port "
                           f"{SCHEDULER_PORT} by default") from None
    if not host or not 0 < port < 65536:
        raise ClusterError(f"scheduler {address}: not an address of the form "
                           f"{scheme}://HOST:PORT (host {host!r}, port {port}); a scheduler "
                           f"listens on port {SCHEDULER_PORT} by default")
    return scheme, host, port


def _web_address(address: str) -> str:
    """The message for an http(s):// address, giving the scheduler's on the same host."""
    from urllib.parse import urlsplit

    try:
        host = urlsplit(address).hostname or "HOST"
    except ValueError:
        host = "HOST"
    return (f"scheduler {address} is a web address (the dashboard's, port {DASHBOARD_PORT} by "
            f"default), not a scheduler's: give tcp://{host}:{SCHEDULER_PORT} (the scheduler's "
            f"default port; tls://{host}:PORT for a TLS scheduler)")


def probe(address: str, security) -> None:
    """Refuse, in one ClusterError line within CONNECT_TIMEOUT, an address where no dask
    scheduler answers: nothing listening, a web server, a TLS server reached without TLS or
    a plain one with it, certificates missing, untrusted or refused."""
    scheme, host, port = check_address(address)
    if scheme == "tcp" and security.require_encryption:
        raise ClusterError(f"scheduler {address}: dask's configuration requires encryption "
                           "(distributed.comm.require-encryption): give its tls:// address")
    context = tls_context(address, security) if scheme == "tls" else None
    deadline = time.monotonic() + CONNECT_TIMEOUT
    with _connection(address, host, port) as raw:
        sock = raw if context is None else _tls_handshake(raw, context, security, address,
                                                          host, deadline)
        with sock:
            try:
                first = _answer(sock, deadline)
            except ssl.SSLError as err:  # TLS 1.3: the refusal of our certificate comes now
                raise ClusterError(_tls_failure(address, security, err)) from None
            _judge(address, scheme, host, port, first, deadline)
            _complete_handshake(sock, first, deadline)


def tls_context(address: str, security) -> ssl.SSLContext:
    """The client's TLS context from `security`; ClusterError when its certificates are
    missing, unreadable or unusable."""
    given = {key: getattr(security, field) for _, key, field in TLS_SETTINGS}
    missing = [key for key in list(given)[:2] if not given[key]]  # the key may be in the cert
    if missing:
        raise ClusterError(f"scheduler {address} needs TLS certificates, and "
                           f"{' and '.join(missing)} {'is' if len(missing) == 1 else 'are'} "
                           f"not set: give {TLS_HINT}")
    for key, value in given.items():
        if value and "\n" not in value:  # a value with newlines is the PEM itself
            check_readable(value, f"dask's configuration {key} =")
    try:
        return security.get_connection_args("client")["ssl_context"]
    except (OSError, ValueError) as err:  # ssl.SSLError is an OSError
        raise ClusterError(f"scheduler {address}: cannot use the TLS certificate "
                           f"{_pem_name(security.tls_client_cert)} with the key "
                           f"{_pem_name(security.tls_client_key)} and the authority "
                           f"{_pem_name(security.tls_ca_file)} ({_reason(err)})") from None


@contextmanager
def _connection(address: str, host: str, port: int):
    """A TCP connection to host:port, or ClusterError saying why there is none."""
    try:
        sock = socket.create_connection((host, port), timeout=CONNECT_TIMEOUT)
    except ConnectionRefusedError:
        raise ClusterError(f"scheduler {address}: nothing listens there (connection refused); "
                           f"check the address, or {START_HINT}") from None
    except TimeoutError:
        raise ClusterError(f"scheduler {address}: no answer within {CONNECT_TIMEOUT:g} s; "
                           f"check the address and the firewall, or {START_HINT}") from None
    except OSError as err:  # unknown host, unreachable network...
        raise ClusterError(f"scheduler {address}: cannot connect ({_reason(err)}); check the "
                           f"address, or {START_HINT}") from None
    with sock:
        yield sock


def _tls_handshake(sock, context, security, address: str, host: str, deadline: float):
    """`sock` wrapped in TLS, or ClusterError: the scheduler's certificate untrusted, ours
    refused, or no TLS server there."""
    sock.settimeout(max(deadline - time.monotonic(), 0.01))
    try:
        return context.wrap_socket(sock, server_hostname=host)
    except ssl.SSLCertVerificationError as err:
        ca = _pem_name(security.tls_ca_file)
        raise ClusterError(f"scheduler {address}: its certificate is not signed by the "
                           f"authority in {ca} ({err.verify_message}): give the certificate "
                           "authority that signed the scheduler's") from None
    except ssl.SSLError as err:
        if "ALERT" in (err.reason or ""):  # TLS 1.2: the server refuses our certificate here
            raise ClusterError(_tls_failure(address, security, err)) from None
        raise ClusterError(_not_tls(address, err)) from None
    except TimeoutError:
        raise ClusterError(f"scheduler {address}: no TLS handshake within "
                           f"{CONNECT_TIMEOUT:g} s, so no TLS scheduler there (the dashboard?); "
                           f"a scheduler listens on port {SCHEDULER_PORT} by default") from None
    except OSError as err:  # closed or reset during the handshake
        raise ClusterError(_not_tls(address, err)) from None


def _not_tls(address: str, err) -> str:
    """The message for a tls:// address where the server does not speak TLS."""
    tcp = address.replace("tls://", "tcp://", 1)
    return (f"scheduler {address}: the server there does not speak TLS ({_reason(err)}): give "
            f"{tcp} for a scheduler without TLS (a scheduler listens on port {SCHEDULER_PORT} "
            f"by default, its dashboard on {DASHBOARD_PORT})")


def _tls_failure(address: str, security, err: ssl.SSLError) -> str:
    """The message for a TLS error from the scheduler: an alert refuses this client's
    certificate."""
    if "ALERT" not in (err.reason or ""):
        return f"scheduler {address}: the TLS connection failed ({_reason(err)})"
    return (f"scheduler {address} refused this client's certificate "
            f"{_pem_name(security.tls_client_cert)} ({_reason(err)}): it must be signed by the "
            "certificate authority the scheduler trusts (its --tls-ca-file)")


def _answer(sock, deadline: float) -> bytes | None:
    """The server's first bytes (up to 8): unprompted, as a dask scheduler greets, else in
    reply to an HTTP request, which a web server waits for. b"": it closed; None: silence."""
    first = _receive(sock, 8, min(deadline, time.monotonic() + GREETING_WAIT))
    if first is not None:
        return first
    try:
        sock.sendall(HTTP_REQUEST)
    except ConnectionError:
        return b""
    return _receive(sock, 8, deadline)


def _receive(sock, n: int, until: float) -> bytes | None:
    """Up to n bytes, fewer if the peer closes (b"": closed before sending any); None when
    nothing came before `until`."""
    data = b""
    while len(data) < n:
        left = until - time.monotonic()
        if left <= 0:
            break
        sock.settimeout(left)
        try:
            chunk = sock.recv(n - len(data))
        except TimeoutError:
            break
        except ConnectionError:  # reset: as closed
            chunk = b""
        if not chunk:
            return data
        data += chunk
    return data or None


def _judge(address: str, scheme: str, host: str, port: int, first: bytes | None,
           deadline: float) -> None:
    """ClusterError unless `first` begins a dask greeting: 8 bytes, the message's length."""
    if first is None:
        raise ClusterError(f"scheduler {address}: something listens there but does not answer "
                           f"as a dask scheduler within {CONNECT_TIMEOUT:g} s; check the "
                           f"address (a scheduler listens on port {SCHEDULER_PORT} by default)")
    if first.startswith(b"HTTP/"):
        raise ClusterError(f"scheduler {address} is a web server (it answers HTTP), not a dask "
                           f"scheduler: the dashboard listens on port {DASHBOARD_PORT} by "
                           f"default, the scheduler on {scheme}://{host}:{SCHEDULER_PORT}")
    if not first:
        if scheme == "tcp" and _speaks_tls(host, port, deadline):
            raise ClusterError(f"scheduler {address} speaks TLS: give tls://{host}:{port} "
                               f"instead, with certificates ({TLS_HINT})")
        raise ClusterError(f"scheduler {address}: the server there closed the connection "
                           "without greeting as a dask scheduler does; check the address")
    if len(first) < 8 or not 0 < struct.unpack("Q", first)[0] < MAX_GREETING:
        raise ClusterError(f"scheduler {address}: the server there answers, but not as a dask "
                           f"scheduler (it sent {first!r}); check the address")


def _speaks_tls(host: str, port: int, deadline: float) -> bool:
    """Whether a TLS server listens at host:port (a handshake without certificates gets as
    far as its answer)."""
    context = ssl.SSLContext(ssl.PROTOCOL_TLS_CLIENT)
    context.check_hostname, context.verify_mode = False, ssl.CERT_NONE
    try:
        with socket.create_connection((host, port), timeout=max(deadline - time.monotonic(),
                                                                 0.01)) as sock, \
                context.wrap_socket(sock):
            return True
    except ssl.SSLError as err:
        return "ALERT" in (err.reason or "")  # refused our (absent) certificate: TLS
    except OSError:
        return False


def _complete_handshake(sock, first: bytes, deadline: float) -> None:
    """Send the scheduler its own greeting back, a valid handshake, so that it logs nothing
    (otherwise: "closed before handshake completed"); a failure here is harmless."""
    (size,) = struct.unpack("Q", first)
    rest = _receive(sock, size, deadline) or b""
    if len(rest) == size:
        try:
            sock.sendall(first + rest)
        except OSError:
            pass


def _pem_name(value) -> str:
    """A certificate or key setting as the messages name it: its path."""
    if not value:
        return "(none: in the certificate file)"
    return "(PEM in memory)" if "\n" in value else str(value)


def _reason(err) -> str:
    """An OSError's reason in a few words."""
    if isinstance(err, ssl.SSLError) and err.reason:
        return err.reason.lower().replace("_", " ")
    return _one_line(err.strerror if getattr(err, "strerror", None) else err)


def _one_line(err) -> str:
    """An error's text on one line."""
    return " ".join(str(err).split()) or type(err).__name__


def check_workers(client) -> None:
    """Refuse a cluster without workers, with workers lacking the project, or at another
    version of it (ClusterError)."""
    from .provenance import engine_fingerprint

    address = client.scheduler.address
    tls = " --tls-ca-file FILE --tls-cert FILE --tls-key FILE" \
        if address.startswith("tls://") else ""
    try:
        client.wait_for_workers(1, timeout=WORKERS_TIMEOUT)
    except TimeoutError:
        raise ClusterError(f"scheduler {address} has no workers after {WORKERS_TIMEOUT:g} s: "
                           f"start some with `dask worker {address} --nthreads 1{tls}` on "
                           "machines where this project is installed") from None
    found = _answers(client, CAN_IMPORT, address)
    missing = sorted(worker for worker, ok in found.items() if ok is not True)
    if missing:
        raise ClusterError(f"workers {', '.join(missing)} cannot import this project "
                           "(engine, pipeline): install it on every worker machine at the same "
                           "commit (`pip install -e /path/to/bumpers`) and restart the workers")
    mine = engine_fingerprint()
    theirs = _answers(client, FINGERPRINT, address)
    other = sorted(worker for worker, fingerprint in theirs.items() if fingerprint != mine)
    if other:
        raise ClusterError(f"workers {', '.join(other)} run another version of this project "
                           f"(engine fingerprint differs from {mine[:12]}): install the same "
                           "commit on every worker and restart them")


def _answers(client, code: str, address: str) -> dict:
    """Each worker's answer to `code` (evaluated there), leaving out the workers that could not
    be reached: a worker that died since the scheduler listed it is gone, not a worker of
    another version (the scheduler gives its work to the others). ClusterError when none
    answers."""
    import asyncio

    gone = (OSError, TimeoutError, asyncio.TimeoutError)  # dask's CommClosedError is an OSError
    found = client.run(eval, code, on_error="return")
    answers = {worker: answer for worker, answer in found.items()
               if not isinstance(answer, gone)}
    if found and not answers:
        raise ClusterError(f"no worker of scheduler {address} could be reached (all of them "
                           "died or left while being checked): start workers and run again")
    return answers
