//! The worst flights of a campaign: the largest misses first.

use super::types::Flight;

/// Positions in `flights` of the `n` largest misses, largest first; a non-finite miss counts
/// as the largest, equal misses go by case id.
#[must_use]
pub fn worst_flights(flights: &[Flight], n: usize) -> Vec<usize> {
    let key = |f: &Flight| {
        if f.miss_km.is_finite() {
            f.miss_km
        } else {
            f64::INFINITY
        }
    };
    let mut order: Vec<usize> = (0..flights.len()).collect();
    order.sort_by(|&a, &b| match (flights.get(a), flights.get(b)) {
        (Some(fa), Some(fb)) => key(fb).total_cmp(&key(fa)).then(fa.id.cmp(&fb.id)),
        _ => std::cmp::Ordering::Equal,
    });
    order.truncate(n);
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flight(id: u32, miss_km: f64) -> Flight {
        Flight {
            id,
            miss_km,
            downrange_km: miss_km,
            crossrange_km: 0.0,
            limit_ratios: [0.5; 3],
        }
    }

    /// Largest misses first, NaN as the largest, ties by id; fewer flights than asked.
    #[test]
    fn worst_selection() {
        let f = [
            flight(0, 1.0),
            flight(1, 9.0),
            flight(2, f64::NAN),
            flight(3, 4.0),
            flight(4, 9.0),
            flight(5, 0.5),
        ];
        let ids = |n| -> Vec<u32> { worst_flights(&f, n).iter().map(|&i| f[i].id).collect() };
        assert_eq!(ids(3), vec![2, 1, 4]);
        assert_eq!(ids(5), vec![2, 1, 4, 3, 0]);
        assert_eq!(ids(10).len(), 6);
        assert!(worst_flights(&[], 5).is_empty());
    }
}
