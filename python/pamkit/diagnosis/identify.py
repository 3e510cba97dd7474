"""Which fitted parameters the data determine, and what the others trade against.

A least-squares fit's 95 % interval comes from its Jacobian J at the solution: the covariance
(JᵀJ)⁻¹, or the sandwich around it when residuals are correlated (calibrate.cluster_intervals).
Where J is rank-deficient — a parameter the prediction does not depend on (a fibre count where the
fibres have no thickness), or two that move it the same way (a braid angle and a membrane modulus
on a map too short to tell them apart) — a pseudo-inverse gives that direction *zero* variance,
and the parameter comes out with an interval of zero width: a claim of perfect knowledge exactly
where there is none. Here such a direction is found and named instead:

- numerically null: a singular value of J below NULL_RTOL of the largest;
- or wider than the search: its 95 % interval along the direction spans more than the whole
  search box (moving across the box changes the fit by less than its noise).

A coordinate with a component above TRADES in such a direction is *not determined*: its interval
is its whole search interval, and it trades against the other coordinates of that direction (none:
the data do not depend on it at all).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# Singular values below this share of the largest are numerical zeros (double precision's
# Jacobians by sensitivities or differences are good to about 1e-7 relative).
NULL_RTOL = 1e-7
# A direction's component this large in a coordinate ties that coordinate to the direction.
TRADES = 0.1
# The two-sided 95 % quantile of the normal distribution, to the two decimals of every other 95 %
# interval the diagnosis reports (the jackknife's, the bootstrap's normal approximations).
Z95 = 1.96


@dataclass
class Identification:
    """The covariance of a fit's coordinates (in the fit's unit box) over the directions the data
    determine, and the coordinates they do not."""

    covariance: np.ndarray  # k x k, zero along undetermined directions
    undetermined: dict[int, list[int]]  # coordinate index -> indices it trades against

    def trades_against(self, names: list[str]) -> dict[str, list[str]]:
        """`undetermined` by name."""
        return {names[i]: [names[j] for j in partners] for i, partners in self.undetermined.items()}


def identify(jacobian: np.ndarray, meat: np.ndarray | None = None, widths: bool = True) -> Identification:
    """Splits the directions of a fit's coordinate box into determined and undetermined ones.

    Parameters
    ----------
    jacobian : (n, k) array
        The residuals' Jacobian at the solution, residuals in units of their noise and coordinates
        in the unit box of their search intervals.
    meat : (k, k) array, optional
        The middle of a sandwich covariance (Σ_g J_gᵀ r_g r_gᵀ J_g, scaled); None: the residuals are
        independent with unit variance, and the covariance is (JᵀJ)⁻¹.
    widths : bool
        Whether a direction whose interval spans the box counts as undetermined (the residuals are
        in units of their noise); False leaves only the numerically null directions.
    """
    k = jacobian.shape[1]
    if k == 0:
        return Identification(np.zeros((0, 0)), {})
    # The right singular vectors only: U would be n x n, and a time series has 10^4-10^5 residuals.
    # More coordinates than residuals: the thin SVD lacks k - n directions, all null.
    rows = jacobian if jacobian.shape[0] >= k else np.vstack([jacobian, np.zeros((k - jacobian.shape[0], k))])
    _, s, vt = np.linalg.svd(rows, full_matrices=False)
    v = vt.T
    largest = float(s.max())
    kept = s > NULL_RTOL * largest if largest > 0 else np.zeros(k, dtype=bool)
    inverse = np.zeros(k)
    inverse[kept] = 1.0 / s[kept] ** 2
    bread = (v * inverse) @ v.T
    covariance = bread if meat is None else bread @ meat @ bread
    null = [i for i in range(k) if not kept[i]]
    # A direction the data hold is undetermined all the same when its interval spans the box.
    for i in np.flatnonzero(kept) if widths else ():
        spread = float(v[:, i] @ covariance @ v[:, i])
        if Z95 * np.sqrt(max(spread, 0.0)) >= 1.0:
            null.append(int(i))
    basis = [v[:, i] for i in null]
    undetermined: dict[int, list[int]] = {}
    for direction in basis:
        tied = [j for j in range(k) if abs(direction[j]) > TRADES]
        for j in tied:
            partners = undetermined.setdefault(j, [])
            partners += [other for other in tied if other != j and other not in partners]
    for j in undetermined:
        covariance[j, :] = 0.0
        covariance[:, j] = 0.0
    return Identification(covariance, undetermined)


def interval_numbers(value: float, low: float, high: float, digits: int = 4) -> tuple[str, str, str]:
    """A value and its interval's ends as printed: `digits` significant digits, more where fewer would
    print a narrow interval's ends alike (a narrow interval is not a zero-width one), up to 9."""
    while digits < 9 and f"{low:.{digits}g}" == f"{high:.{digits}g}" and low != high:
        digits += 1
    return f"{value:.{digits}g}", f"{low:.{digits}g}", f"{high:.{digits}g}"


def why_undetermined(partners: list[str], at_bound: bool) -> str:
    """Why a value is not determined, in words: what it trades against, a bound that holds it, or a
    prediction that does not depend on it."""
    if partners:
        return f"it trades against {', '.join(partners)}"
    if at_bound:
        return "it ends at its search bound however the data are split: they would take it further"
    return "the prediction does not depend on it"
