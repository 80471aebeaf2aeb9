//! The text of a hypervolume reference point (`--ref` of `host-sim hypervolume` and
//! `optimize`, and of `reentry-dask optimize`): one parser for every front end
//! (comma-separated finite numbers, one per objective; the dimension is checked against the
//! front or problem by [`super::run::check_reference`]).

/// A malformed `--ref` value.
#[derive(Debug, thiserror::Error)]
#[error("command line: --ref {value:?}: coordinate {coordinate}: {reason}")]
pub struct ReferenceArgError {
    /// The argument's text.
    pub value: String,
    /// Coordinate number, from 1.
    pub coordinate: usize,
    /// What is wrong with it.
    pub reason: &'static str,
}

/// Parse `--ref`: comma-separated finite numbers (`1.1,1.1`; spaces around a number allowed).
///
/// # Errors
/// [`ReferenceArgError`] naming the first coordinate that is not a number or not finite.
pub fn parse_reference(s: &str) -> Result<Vec<f64>, ReferenceArgError> {
    let bad = |coordinate, reason| ReferenceArgError {
        value: s.to_string(),
        coordinate,
        reason,
    };
    s.split(',')
        .enumerate()
        .map(|(k, f)| match f.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(bad(k + 1, "must be finite")),
            Err(_) => Err(bad(k + 1, "not a number")),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::parse_reference;

    #[test]
    fn reference_is_finite_numbers_separated_by_commas() {
        assert_eq!(
            parse_reference("1.1, 2e0,-3").unwrap(),
            vec![1.1, 2.0, -3.0]
        );
        let e = parse_reference("1,nan").unwrap_err();
        assert_eq!((e.coordinate, e.reason), (2, "must be finite"));
        let e = parse_reference("1,,").unwrap_err();
        assert_eq!((e.coordinate, e.reason), (2, "not a number"));
        let e = parse_reference("inf").unwrap_err();
        assert_eq!((e.coordinate, e.reason), (1, "must be finite"));
    }
}
