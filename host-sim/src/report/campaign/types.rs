//! The data the campaign figures take: the flights of one mode ([`ModeReport`]) and the
//! counts of worst flights labelled and traced.

/// One flight of a mode, at the terminal interface.
#[derive(Clone, Debug, PartialEq)]
pub struct Flight {
    /// Case id (index in the campaign).
    pub id: u32,
    /// Miss distance \[km\].
    pub miss_km: f64,
    /// Downrange error (positive: long) \[km\].
    pub downrange_km: f64,
    /// Crossrange error (positive: right) \[km\].
    pub crossrange_km: f64,
    /// Peak / limit of heat flux, g-load and g-load rate \[-\].
    pub limit_ratios: [f64; 3],
}

/// One point of a flight's error history.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TracePoint {
    /// Time to go to the flight's end \[s\].
    pub time_to_go_s: f64,
    /// Downrange error \[km\].
    pub downrange_km: f64,
    /// Crossrange error \[km\].
    pub crossrange_km: f64,
}

/// The error history of one (worst) flight.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorTrace {
    /// Case id.
    pub id: u32,
    /// Its miss distance \[km\].
    pub miss_km: f64,
    /// Points, in time order.
    pub points: Vec<TracePoint>,
}

/// What the figures of one mode show.
#[derive(Clone, Debug, PartialEq)]
pub struct ModeReport {
    /// Scenario name (titles).
    pub scenario: String,
    /// Mode name (titles and file names).
    pub mode: String,
    /// The mode's flights (failed ones are not flights).
    pub flights: Vec<Flight>,
    /// Flights that failed (named in the titles).
    pub failed: usize,
    /// The undispersed flight's (downrange, crossrange) error \[km\].
    pub nominal_km: Option<(f64, f64)>,
    /// Error histories of the worst flights, worst first.
    pub traces: Vec<ErrorTrace>,
    /// How the downrange and the crossrange error histories are referenced (notes in the
    /// panels' titles).
    pub trace_reference: [String; 2],
}

/// Worst cases labelled on the footprint.
pub const LABELLED_WORST: usize = 5;

/// Worst flights whose error history is drawn.
pub const TRACED_WORST: usize = 10;

/// "N flights" with the failed ones, for titles.
pub(super) fn flights_note(r: &ModeReport) -> String {
    if r.failed > 0 {
        format!("{} flights, {} failed", r.flights.len(), r.failed)
    } else {
        format!("{} flights", r.flights.len())
    }
}
