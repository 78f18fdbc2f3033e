"""What a point-set function did: `wavejets.Report`."""

from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Report:
    """What a call of a point-set function did (returned with ``return_report=True``).

    Points that could not be fitted (too few neighbors, a degenerate neighborhood) keep their
    input value in the results (zero where there is none); ``fitted`` tells which.
    """

    number_of_points: int
    number_of_fitted_points: int
    number_of_unfitted_points: int
    number_of_non_finite_points: int
    number_of_reduced_order_points: int
    number_of_clamped_points: int
    moves_points: bool
    fitted: np.ndarray = field(repr=False)

    def __str__(self):
        s = (f"{self.number_of_points} points, {self.number_of_fitted_points} fitted, "
             f"{self.number_of_unfitted_points} not fitted, "
             f"{self.number_of_reduced_order_points} at reduced order")
        if self.moves_points:
            s += f", {self.number_of_clamped_points} clamped"
        return s
