//! A general chart helper for the report figures: a [`Figure`] is a grid of [`Panel`]s, each
//! a list of [`Layer`]s (lines, dots, crosses, bars, vertical lines, text labels) drawn on
//! linear axes rounded out to "nice" tick steps, rendered by the same code to SVG
//! ([`Figure::svg`]) and PNG ([`Figure::png`]) through `plotters`, with the embedded font of
//! `report::plot`. The campaign figures ([`super::campaign`]) are built from it.

mod bounds;
mod render;
mod types;

use super::ReportError;

pub use types::{BLACK, Figure, LIMIT_RED, Layer, Legend, Mark, PALETTE, Panel, Rgb};

impl Figure {
    /// The figure as a standalone SVG document.
    ///
    /// # Errors
    /// [`ReportError::Plot`] naming `name` if `plotters` fails.
    pub fn svg(&self, name: &str) -> Result<String, ReportError> {
        render::svg(self).map_err(|source| ReportError::Plot {
            name: name.to_string(),
            source,
        })
    }

    /// The figure as a PNG image (8-bit RGB, [`Figure::size`] pixels).
    ///
    /// # Errors
    /// [`ReportError::Plot`] naming `name` if `plotters` fails or the PNG cannot be encoded.
    pub fn png(&self, name: &str) -> Result<Vec<u8>, ReportError> {
        render::png(self).map_err(|source| ReportError::Plot {
            name: name.to_string(),
            source,
        })
    }

    /// The figure as its two files, `[(stem.svg, bytes), (stem.png, bytes)]`.
    ///
    /// # Errors
    /// As [`Figure::svg`] and [`Figure::png`].
    pub fn files(&self, stem: &str) -> Result<[(String, Vec<u8>); 2], ReportError> {
        let svg = format!("{stem}.svg");
        let png = format!("{stem}.png");
        Ok([
            (svg.clone(), self.svg(&svg)?.into_bytes()),
            (png.clone(), self.png(&png)?),
        ])
    }
}
