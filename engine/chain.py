"""The chain of springs or dashpots a shear building is assembled from, level by level."""
import numpy as np


def chain_matrix(springs: np.ndarray) -> np.ndarray:
    """Assemble a chain of springs (or dashpots): element 0 joins ground to level 0,
    element i joins level i-1 to level i."""
    n = len(springs)
    mat = np.zeros((n, n))
    for i, s in enumerate(springs):
        mat[i, i] += s
        if i > 0:
            mat[i - 1, i - 1] += s
            mat[i - 1, i] -= s
            mat[i, i - 1] -= s
    return mat
