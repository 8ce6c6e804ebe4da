"""Comparing spectra in the tests: eigenvalues as sorted complex lists."""


def pairs(ev) -> list[complex]:
    return sorted((complex(v) for v in ev), key=lambda z: (round(z.real, 9), round(z.imag, 9)))


def close_eigs(ev, expected, tol=1e-12) -> bool:
    a, b = pairs(ev), pairs(expected)
    return len(a) == len(b) and all(abs(u - v) < tol for u, v in zip(a, b, strict=True))
