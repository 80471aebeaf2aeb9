//! Mach x angle-of-attack coefficient tables with bilinear interpolation, clamped at the
//! edges, and the treatment of unpublished (empty) cells.

/// Why a table could not be built. `axis`/`row` name the offending input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TableError {
    /// An axis is empty, not finite or not strictly increasing.
    #[error("axis `{axis}` must be non-empty, finite and strictly increasing")]
    BadAxis {
        /// `mach` or `alpha`.
        axis: &'static str,
    },
    /// A row has the wrong length or a non-finite value.
    #[error("`{name}` row {row}: expected {expected} finite values")]
    BadRow {
        /// `cl` or `cd`.
        name: &'static str,
        /// Row index (Mach index).
        row: usize,
        /// Expected length (number of alpha points).
        expected: usize,
    },
    /// The number of rows differs from the number of Mach points.
    #[error("`{name}`: expected {expected} rows (one per Mach number), found {found}")]
    RowCount {
        /// `cl` or `cd`.
        name: &'static str,
        /// Expected rows.
        expected: usize,
        /// Rows found.
        found: usize,
    },
    /// A whole table has no published value to fill gaps from.
    #[error("`{name}`: no published value to fill the gaps from")]
    Unfillable {
        /// `cl` or `cd`.
        name: &'static str,
    },
}

/// How unpublished (empty) cells of a table are filled before interpolation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GapFill {
    /// Take the alpha increments of the neighbouring Mach column: at Mach column i, a missing
    /// C(i, j) = C(i, j-1) + [C(i', j) - C(i', j-1)], with i' the next higher Mach column
    /// (already filled, processing from high to low Mach); if no higher column exists the next
    /// lower one is used. Leading gaps (at the smallest alpha) use the same rule downward in
    /// alpha. This keeps the shape of the curve of the nearest Mach number.
    #[default]
    NeighbourMachIncrement,
    /// Hold the last published value in alpha at the same Mach number (nearest published
    /// value below; for leading gaps, the first published value above).
    HoldLastAlpha,
}

/// A point's place in a table grid: lower Mach index and fraction, lower alpha index and
/// fraction (see [`CoefficientTable::cell`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    i: usize,
    fm: f64,
    j: usize,
    fa: f64,
}

/// A rectangular table C(Mach, alpha): bilinear interpolation, clamped to the edges.
#[derive(Clone, Debug, PartialEq)]
pub struct CoefficientTable {
    mach: Vec<f64>,
    alpha_rad: Vec<f64>,
    /// Row-major values: `values[i * alpha_rad.len() + j]` at mach\[i\], alpha\[j\] (one
    /// allocation, one indirection per lookup).
    values: Vec<f64>,
}

fn check_axis(axis: &'static str, v: &[f64]) -> Result<(), TableError> {
    let ok = !v.is_empty()
        && v.iter().all(|x| x.is_finite())
        && v.windows(2).all(|w| matches!(w, [a, b] if b > a));
    if ok {
        Ok(())
    } else {
        Err(TableError::BadAxis { axis })
    }
}

/// Index of the lower grid point and the fraction in [0, 1] for `x` clamped to the axis.
/// A NaN `x` gives fraction NaN (the result is then NaN, never a panic).
fn locate(axis: &[f64], x: f64) -> (usize, f64) {
    let (Some(&first), Some(&last)) = (axis.first(), axis.last()) else {
        return (0, f64::NAN);
    };
    if axis.len() == 1 {
        return (0, if x.is_nan() { f64::NAN } else { 0.0 });
    }
    if x.is_nan() {
        return (0, f64::NAN);
    }
    // At or beyond an end (the common case of Mach above the table's last point): the
    // values the search below gives there, without it.
    if x >= last {
        return (axis.len() - 2, 1.0);
    }
    if x <= first {
        return (0, 0.0);
    }
    // Last index i with axis[i] <= x (first < x < last, so 0 <= i <= len - 2): a linear
    // scan, cheaper than a binary search on the few points of an aerodynamic table.
    let inner = axis.get(1..axis.len() - 1).unwrap_or(&[]);
    let i = inner.iter().take_while(|&&a| a <= x).count();
    match (axis.get(i), axis.get(i + 1)) {
        (Some(&a), Some(&b)) => (i, ((x - a) / (b - a)).clamp(0.0, 1.0)),
        _ => (0, f64::NAN),
    }
}

impl CoefficientTable {
    /// Table from axes (Mach [-], alpha \[rad\]) and rows `values\[i\]\[j\]` at (mach\[i\], alpha\[j\]).
    ///
    /// # Errors
    /// Bad axes, wrong row count or length, non-finite values.
    pub fn new(
        name: &'static str,
        mach: Vec<f64>,
        alpha_rad: Vec<f64>,
        values: Vec<Vec<f64>>,
    ) -> Result<Self, TableError> {
        check_axis("mach", &mach)?;
        check_axis("alpha", &alpha_rad)?;
        if values.len() != mach.len() {
            return Err(TableError::RowCount {
                name,
                expected: mach.len(),
                found: values.len(),
            });
        }
        for (row, r) in values.iter().enumerate() {
            if r.len() != alpha_rad.len() || !r.iter().all(|x| x.is_finite()) {
                return Err(TableError::BadRow {
                    name,
                    row,
                    expected: alpha_rad.len(),
                });
            }
        }
        Ok(Self {
            mach,
            alpha_rad,
            values: values.into_iter().flatten().collect(),
        })
    }

    /// Table with unpublished cells (`None`) filled according to `fill`.
    ///
    /// # Errors
    /// As [`CoefficientTable::new`], and [`TableError::Unfillable`] if a gap cannot be filled
    /// (a table without any published value in a gap's row and neighbouring rows).
    pub fn with_gaps(
        name: &'static str,
        mach: Vec<f64>,
        alpha_rad: Vec<f64>,
        cells: Vec<Vec<Option<f64>>>,
        fill: GapFill,
    ) -> Result<Self, TableError> {
        check_axis("mach", &mach)?;
        check_axis("alpha", &alpha_rad)?;
        if cells.len() != mach.len() {
            return Err(TableError::RowCount {
                name,
                expected: mach.len(),
                found: cells.len(),
            });
        }
        if let Some(row) = cells.iter().position(|r| r.len() != alpha_rad.len()) {
            return Err(TableError::BadRow {
                name,
                row,
                expected: alpha_rad.len(),
            });
        }
        let filled = match fill {
            GapFill::HoldLastAlpha => fill_hold(&cells),
            GapFill::NeighbourMachIncrement => fill_increment(&cells),
        };
        let values = filled
            .into_iter()
            .map(|r| r.into_iter().collect::<Option<Vec<f64>>>())
            .collect::<Option<Vec<_>>>()
            .ok_or(TableError::Unfillable { name })?;
        Self::new(name, mach, alpha_rad, values)
    }

    /// Bilinear interpolation at (`mach`, `alpha_rad`), both clamped to the table's range.
    #[must_use]
    pub fn value(&self, mach: f64, alpha_rad: f64) -> f64 {
        self.value_in(&self.cell(mach, alpha_rad))
    }

    /// Where (`mach`, `alpha_rad`) falls in this table's grid: the lookup of
    /// [`CoefficientTable::value`], done once for every table on the same axes
    /// ([`CoefficientTable::same_axes`]).
    #[must_use]
    pub fn cell(&self, mach: f64, alpha_rad: f64) -> Cell {
        let (i, fm) = locate(&self.mach, mach);
        let (j, fa) = locate(&self.alpha_rad, alpha_rad);
        Cell { i, fm, j, fa }
    }

    /// Bilinear interpolation in a cell of this table's grid (from [`CoefficientTable::cell`]
    /// of this table or of one with the same axes).
    #[must_use]
    pub fn value_in(&self, cell: &Cell) -> f64 {
        let Cell { i, fm, j, fa } = *cell;
        let na = self.alpha_rad.len();
        let i1 = (i + 1).min(self.mach.len() - 1);
        let j1 = (j + 1).min(na - 1);
        // Rows i and i1; a cell of a table with other axes gives NaN, never another row's
        // value.
        let row = |i: usize| self.values.get(i * na..(i + 1) * na);
        let (Some(r0), Some(r1)) = (row(i), row(i1)) else {
            return f64::NAN;
        };
        let (Some(&c00), Some(&c01), Some(&c10), Some(&c11)) =
            (r0.get(j), r0.get(j1), r1.get(j), r1.get(j1))
        else {
            return f64::NAN;
        };
        let lo = c00 + fa * (c01 - c00);
        let hi = c10 + fa * (c11 - c10);
        if i1 == i { lo } else { lo + fm * (hi - lo) }
    }

    /// Whether `other` has the same Mach and alpha axes (so one [`Cell`] serves both).
    #[must_use]
    pub fn same_axes(&self, other: &Self) -> bool {
        self.mach == other.mach && self.alpha_rad == other.alpha_rad
    }

    /// The Mach axis [-].
    #[must_use]
    pub fn mach(&self) -> &[f64] {
        &self.mach
    }

    /// The angle-of-attack axis \[rad\].
    #[must_use]
    pub fn alpha_rad(&self) -> &[f64] {
        &self.alpha_rad
    }
}

/// Hold the nearest published value in alpha (below, else above) within each Mach row.
fn fill_hold(cells: &[Vec<Option<f64>>]) -> Vec<Vec<Option<f64>>> {
    cells
        .iter()
        .map(|row| {
            let mut out = row.clone();
            let mut last = None;
            for c in &mut out {
                match c {
                    Some(v) => last = Some(*v),
                    None => *c = last,
                }
            }
            let mut next = None;
            for c in out.iter_mut().rev() {
                match c {
                    Some(v) => next = Some(*v),
                    None => *c = next,
                }
            }
            out
        })
        .collect()
}

/// Fill row `i` from the (already filled) neighbour row `n` using its alpha increments.
fn fill_row_from(row: &mut [Option<f64>], neighbour: &[Option<f64>]) {
    // Upward in alpha: C(i,j) = C(i,j-1) + [C(n,j) - C(n,j-1)].
    for j in 1..row.len() {
        if row[j].is_none()
            && let (Some(prev), Some(nj), Some(nprev)) =
                (row[j - 1], neighbour[j], neighbour[j - 1])
        {
            row[j] = Some(prev + (nj - nprev));
        }
    }
    // Leading gaps, downward: C(i,j) = C(i,j+1) - [C(n,j+1) - C(n,j)].
    for j in (0..row.len().saturating_sub(1)).rev() {
        if row[j].is_none()
            && let (Some(next), Some(nj), Some(nnext)) =
                (row[j + 1], neighbour[j], neighbour[j + 1])
        {
            row[j] = Some(next - (nnext - nj));
        }
    }
}

fn fill_increment(cells: &[Vec<Option<f64>>]) -> Vec<Vec<Option<f64>>> {
    let mut out = cells.to_vec();
    let n = out.len();
    // High to low Mach, each from its higher neighbour.
    for i in (0..n.saturating_sub(1)).rev() {
        let (lo, hi) = out.split_at_mut(i + 1);
        if let (Some(row), Some(nb)) = (lo.last_mut(), hi.first()) {
            fill_row_from(row, nb);
        }
    }
    // Low to high Mach for what is left (e.g. gaps in the highest-Mach column).
    for i in 1..n {
        let (lo, hi) = out.split_at_mut(i);
        if let (Some(nb), Some(row)) = (lo.last(), hi.first_mut()) {
            fill_row_from(row, nb);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(values: Vec<Vec<f64>>) -> CoefficientTable {
        CoefficientTable::new("cl", vec![1.0, 2.0, 4.0], vec![0.0, 0.5], values).unwrap()
    }

    #[test]
    fn grid_points_interior_and_clamping() {
        let tab = t(vec![vec![1.0, 2.0], vec![3.0, 5.0], vec![7.0, 11.0]]);
        assert_eq!(tab.value(2.0, 0.5), 5.0);
        assert_eq!(tab.value(4.0, 0.0), 7.0);
        assert!((tab.value(3.0, 0.25) - 0.5 * (4.0 + 9.0)).abs() < 1e-15);
        assert_eq!(tab.value(0.0, -1.0), 1.0);
        assert_eq!(tab.value(9.0, 9.0), 11.0);
        assert!(tab.value(f64::NAN, 0.1).is_nan());
    }

    /// `locate` as it was before its end fast paths and linear scan: clamp, then a binary
    /// search.
    fn locate_by_search(axis: &[f64], x: f64) -> (usize, f64) {
        let x = x.clamp(axis[0], axis[axis.len() - 1]);
        let i = axis
            .partition_point(|&a| a <= x)
            .saturating_sub(1)
            .min(axis.len() - 2);
        (i, ((x - axis[i]) / (axis[i + 1] - axis[i])).clamp(0.0, 1.0))
    }

    #[test]
    fn locate_is_the_clamped_binary_search_bit_for_bit() {
        let axis = [1.2, 1.5, 2.0, 3.0, 5.0, 10.0, 20.0];
        let mut xs = vec![
            -1.0, 0.0, 1.2, 1.2000001, 1.3, 1.5, 4.999, 5.0, 19.99, 20.0, 20.0000001, 27.3, 1e300,
        ];
        xs.extend((0..=2300).map(|k| 0.01 * f64::from(k)));
        for x in xs {
            let (i, f) = locate(&axis, x);
            let (i_ref, f_ref) = locate_by_search(&axis, x);
            assert_eq!((i, f.to_bits()), (i_ref, f_ref.to_bits()), "x = {x}");
        }
        assert!(locate(&axis, f64::NAN).1.is_nan());
        assert_eq!(locate(&axis, f64::INFINITY), (5, 1.0));
        assert_eq!(locate(&axis, f64::NEG_INFINITY), (0, 0.0));
    }

    #[test]
    fn rejects_bad_input() {
        assert!(
            CoefficientTable::new("cl", vec![2.0, 1.0], vec![0.0], vec![vec![0.0]; 2]).is_err()
        );
        assert!(CoefficientTable::new("cl", vec![1.0], vec![0.0, 1.0], vec![vec![0.0]]).is_err());
        assert!(CoefficientTable::new("cl", vec![1.0], vec![0.0], vec![]).is_err());
        assert!(CoefficientTable::new("cl", vec![1.0], vec![0.0], vec![vec![f64::NAN]]).is_err());
    }

    #[test]
    fn single_point_axes_work() {
        let tab = CoefficientTable::new("cd", vec![5.0], vec![0.1], vec![vec![1.3]]).unwrap();
        assert_eq!(tab.value(20.0, 0.7), 1.3);
    }

    #[test]
    fn gap_fills() {
        let cells = vec![
            vec![Some(1.0), Some(2.0), None],
            vec![Some(1.5), Some(3.0), Some(6.0)],
            vec![None, Some(4.0), None],
        ];
        let axes = || (vec![1.0, 2.0, 3.0], vec![0.0, 0.1, 0.2]);
        let (m, a) = axes();
        let inc =
            CoefficientTable::with_gaps("cl", m, a, cells.clone(), GapFill::NeighbourMachIncrement)
                .unwrap();
        // Row 0 from row 1 increments: 2 + (6 - 3) = 5.
        assert_eq!(inc.value(1.0, 0.2), 5.0);
        // Row 2 (highest Mach) from row 1: leading 4 - (3 - 1.5) = 2.5, trailing 4 + 3 = 7.
        assert_eq!(inc.value(3.0, 0.0), 2.5);
        assert_eq!(inc.value(3.0, 0.2), 7.0);
        let (m, a) = axes();
        let hold = CoefficientTable::with_gaps("cl", m, a, cells, GapFill::HoldLastAlpha).unwrap();
        assert_eq!(hold.value(1.0, 0.2), 2.0);
        assert_eq!(hold.value(3.0, 0.0), 4.0);
        assert_eq!(hold.value(3.0, 0.2), 4.0);
        let empty = vec![vec![None, None]];
        assert!(matches!(
            CoefficientTable::with_gaps("cd", vec![1.0], vec![0.0, 1.0], empty, GapFill::default()),
            Err(TableError::Unfillable { name: "cd" })
        ));
    }
}
