//! Histogram bins of a sample.

/// Equal-width bins over `lo..hi`: the edges (`bins + 1`) and the count in each; values
/// outside go to the first or last bin, non-finite ones to none.
#[must_use]
pub fn histogram(values: &[f64], lo: f64, hi: f64, bins: usize) -> (Vec<f64>, Vec<f64>) {
    let bins = bins.max(1);
    let (lo, hi) = if hi > lo { (lo, hi) } else { (lo, lo + 1.0) };
    let w = (hi - lo) / bins as f64;
    let edges = (0..=bins).map(|i| lo + w * i as f64).collect();
    let mut counts = vec![0.0; bins];
    for v in values.iter().filter(|v| v.is_finite()) {
        let k = (((v - lo) / w).floor().max(0.0) as usize).min(bins - 1);
        if let Some(c) = counts.get_mut(k) {
            *c += 1.0;
        }
    }
    (edges, counts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_edges() {
        let (e, c) = histogram(
            &[0.1, 0.2, 0.55, 0.99, 1.0, 7.0, -3.0, f64::NAN],
            0.0,
            1.0,
            2,
        );
        assert_eq!(e, vec![0.0, 0.5, 1.0]);
        assert_eq!(c, vec![3.0, 4.0]);
    }
}
