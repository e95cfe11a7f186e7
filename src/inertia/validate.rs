//! Input checks and small matrix helpers shared by the inertia layer.

use super::InertiaError;
use super::tolerance::{MASS_TENSOR_TOLERANCE, SYMMETRY_TOLERANCE};
use nalgebra::{DMatrix, DVector};

pub(super) fn check_dim(dim: usize, min: usize) -> Result<(), InertiaError> {
    if dim < min {
        Err(InertiaError::DimensionTooSmall { dim, min })
    } else {
        Ok(())
    }
}

pub(super) fn check_finite(
    quantity: &'static str,
    index: Option<usize>,
    value: f64,
) -> Result<(), InertiaError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(InertiaError::NonFinite {
            quantity,
            index,
            value,
        })
    }
}

pub(super) fn check_positive(
    quantity: &'static str,
    index: Option<usize>,
    value: f64,
) -> Result<(), InertiaError> {
    check_finite(quantity, index, value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(InertiaError::NotPositive {
            quantity,
            index,
            value,
        })
    }
}

pub(super) fn check_positive_list(
    quantity: &'static str,
    values: &[f64],
) -> Result<(), InertiaError> {
    if values.is_empty() {
        return Err(InertiaError::Empty { quantity });
    }
    for (i, &v) in values.iter().enumerate() {
        check_positive(quantity, Some(i), v)?;
    }
    Ok(())
}

/// Checks that `v` has length `dim` and finite entries.
pub(super) fn check_point(
    quantity: &'static str,
    index: Option<usize>,
    v: &DVector<f64>,
    dim: usize,
) -> Result<(), InertiaError> {
    if v.len() != dim {
        return Err(InertiaError::LengthMismatch {
            quantity,
            index,
            expected: dim,
            found: v.len(),
        });
    }
    for &x in v.iter() {
        check_finite(quantity, index, x)?;
    }
    Ok(())
}

pub(super) fn check_points(
    quantity: &'static str,
    points: &[DVector<f64>],
) -> Result<usize, InertiaError> {
    let first = points.first().ok_or(InertiaError::Empty { quantity })?;
    let dim = first.len();
    check_dim(dim, 1)?;
    for (i, p) in points.iter().enumerate() {
        check_point(quantity, Some(i), p, dim)?;
    }
    Ok(dim)
}

pub(super) fn symmetrize(m: &DMatrix<f64>) -> DMatrix<f64> {
    (m + m.transpose()) * 0.5
}

pub(super) use crate::numeric::{
    max_abs_matrix as max_abs, sorted_symmetric_eigen as sorted_eigen,
};

/// Returns `Err(WrongShape)` unless `m` is `expected` × `expected` and `size_ok` (a
/// condition on the dimension itself).
pub(super) fn check_square(
    quantity: &'static str,
    m: &DMatrix<f64>,
    expected: usize,
    size_ok: bool,
) -> Result<(), InertiaError> {
    if size_ok && m.nrows() == expected && m.ncols() == expected {
        return Ok(());
    }
    Err(InertiaError::WrongShape {
        quantity,
        rows: m.nrows(),
        cols: m.ncols(),
        expected,
    })
}

/// Checks that every entry of `m` is finite; the index of a bad entry is row · ncols + col.
pub(super) fn check_finite_matrix(
    quantity: &'static str,
    m: &DMatrix<f64>,
) -> Result<(), InertiaError> {
    for r in 0..m.nrows() {
        for c in 0..m.ncols() {
            check_finite(quantity, Some(r * m.ncols() + c), m[(r, c)])?;
        }
    }
    Ok(())
}

/// Checks that `m` (square, finite) is symmetric within [`SYMMETRY_TOLERANCE`], relative to
/// its largest entry.
pub(super) fn check_symmetric(
    quantity: &'static str,
    m: &DMatrix<f64>,
) -> Result<(), InertiaError> {
    let scale = max_abs(m);
    if scale == 0.0 {
        return Ok(());
    }
    let asymmetry = max_abs(&(m - m.transpose())) / scale;
    if asymmetry > SYMMETRY_TOLERANCE {
        return Err(InertiaError::NotSymmetric {
            quantity,
            asymmetry,
        });
    }
    Ok(())
}

/// Checks that no principal second moment is negative beyond round-off
/// ([`MASS_TENSOR_TOLERANCE`] relative to the largest |Jᵢ|).
pub(super) fn check_moments_nonnegative(moments: &[f64]) -> Result<(), InertiaError> {
    let largest = moments.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    for (index, &moment) in moments.iter().enumerate() {
        if moment < -MASS_TENSOR_TOLERANCE * largest {
            return Err(InertiaError::NegativeMoment { index, moment });
        }
    }
    Ok(())
}

/// The principal plane (k, l) with the smallest plane moment Jₖ + Jₗ, its moment and the
/// largest plane moment, when that smallest moment is at most `rel_tol` times the largest
/// (the map is singular); `None` otherwise. `moments` are the principal second moments.
pub(super) fn singular_plane(moments: &[f64], rel_tol: f64) -> Option<((usize, usize), f64, f64)> {
    let n = moments.len();
    let mut smallest: Option<((usize, usize), f64)> = None;
    let mut largest = 0.0f64;
    for a in 0..n {
        for b in a + 1..n {
            let m = moments[a] + moments[b];
            largest = largest.max(m);
            if smallest.is_none_or(|(_, s)| m < s) {
                smallest = Some(((a, b), m));
            }
        }
    }
    let (plane, moment) = smallest?;
    (moment <= rel_tol * largest || moment <= 0.0 || moment.is_nan())
        .then_some((plane, moment, largest))
}
