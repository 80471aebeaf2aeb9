//! The chart's data: colours, marks, layers, panels and figures (what `bounds` and
//! `render` read; the facade renders a [`Figure`]).

/// A colour (8-bit RGB).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

/// Ten distinguishable series colours (matplotlib's "tab10").
pub const PALETTE: [Rgb; 10] = [
    Rgb(0x1f, 0x77, 0xb4),
    Rgb(0xff, 0x7f, 0x0e),
    Rgb(0x2c, 0xa0, 0x2c),
    Rgb(0xd6, 0x27, 0x28),
    Rgb(0x94, 0x67, 0xbd),
    Rgb(0x8c, 0x56, 0x4b),
    Rgb(0xe3, 0x77, 0xc2),
    Rgb(0x7f, 0x7f, 0x7f),
    Rgb(0xbc, 0xbd, 0x22),
    Rgb(0x17, 0xbe, 0xcf),
];

/// Black (targets, labels).
pub const BLACK: Rgb = Rgb(0, 0, 0);

/// The red of limit lines.
pub const LIMIT_RED: Rgb = Rgb(0xd6, 0x27, 0x28);

/// What a layer draws (data coordinates).
#[derive(Clone, Debug, PartialEq)]
pub enum Mark {
    /// A polyline.
    Line {
        /// Points (x, y); non-finite points are dropped.
        points: Vec<(f64, f64)>,
        /// Stroke width \[px\].
        width: u32,
        /// Dashed.
        dashed: bool,
    },
    /// Filled dots.
    Dots {
        /// Points (x, y).
        points: Vec<(f64, f64)>,
        /// Radius \[px\].
        radius: u32,
    },
    /// A cross (a target) at one point.
    Cross {
        /// The point (x, y).
        point: (f64, f64),
        /// Half size \[px\].
        size: i32,
    },
    /// A histogram: bar `i` spans `edges[i]..edges[i + 1]` with height `heights[i]`.
    Bars {
        /// Bin edges, increasing (one more than the heights).
        edges: Vec<f64>,
        /// Bar heights.
        heights: Vec<f64>,
    },
    /// A vertical line across the whole panel at `x`.
    VerticalLine {
        /// Abscissa.
        x: f64,
        /// Dashed.
        dashed: bool,
    },
    /// Text labels next to points (a small dot at the point, the text up and right of it).
    Labels {
        /// (point, text).
        items: Vec<((f64, f64), String)>,
    },
}

/// One layer of a panel: a mark, its colour and its legend entry (`None`: none).
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// Legend entry.
    pub label: Option<String>,
    /// Colour.
    pub colour: Rgb,
    /// What is drawn.
    pub mark: Mark,
}

impl Layer {
    /// A layer with a legend entry.
    #[must_use]
    pub fn new(label: impl Into<String>, colour: Rgb, mark: Mark) -> Self {
        Self {
            label: Some(label.into()),
            colour,
            mark,
        }
    }

    /// A layer without a legend entry.
    #[must_use]
    pub fn unlabelled(colour: Rgb, mark: Mark) -> Self {
        Self {
            label: None,
            colour,
            mark,
        }
    }
}

/// Where a panel's legend goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Legend {
    /// Upper left corner.
    UpperLeft,
    /// Upper right corner.
    UpperRight,
    /// Lower left corner.
    LowerLeft,
    /// Lower right corner.
    LowerRight,
    /// No legend.
    Hidden,
}

/// One chart: title, axis labels (with units), layers and axis options.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// Title.
    pub title: String,
    /// Abscissa label.
    pub x_label: String,
    /// Ordinate label.
    pub y_label: String,
    /// Layers, drawn in order.
    pub layers: Vec<Layer>,
    /// Equal data units per pixel on both axes (a footprint in km: circles stay circles).
    pub equal_aspect: bool,
    /// Abscissa ticks print the negated value (time to go plotted as `-t_go`, so that the
    /// end is on the right and the ticks read positive).
    pub x_negated: bool,
    /// The abscissa's data are base-10 logarithms: the axis spans whole decades and its
    /// ticks print `10^x` (a heavy-tailed miss distribution).
    pub x_log10: bool,
    /// Abscissa range (`None`: the data's, rounded out).
    pub x_range: Option<(f64, f64)>,
    /// Ordinate range (`None`: the data's, rounded out).
    pub y_range: Option<(f64, f64)>,
    /// Legend position.
    pub legend: Legend,
}

impl Panel {
    /// A panel with data ranges, no equal aspect, the legend upper right.
    #[must_use]
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: &str) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            layers: Vec::new(),
            equal_aspect: false,
            x_negated: false,
            x_log10: false,
            x_range: None,
            y_range: None,
            legend: Legend::UpperRight,
        }
    }
}

/// A figure: panels on a grid of `columns` columns (rows as needed), each `panel_size`
/// pixels (SVG user units).
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// Panels, row by row.
    pub panels: Vec<Panel>,
    /// Columns of the grid (>= 1).
    pub columns: usize,
    /// Size of one panel \[px\].
    pub panel_size: (u32, u32),
}

impl Figure {
    /// A figure of one panel of 900 x 640 px.
    #[must_use]
    pub fn single(panel: Panel) -> Self {
        Self {
            panels: vec![panel],
            columns: 1,
            panel_size: (900, 640),
        }
    }

    /// Size of the whole figure \[px\].
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        let cols = self.columns.max(1);
        let rows = self.panels.len().div_ceil(cols).max(1);
        let (w, h) = self.panel_size;
        (
            w.saturating_mul(u32::try_from(cols).unwrap_or(1)),
            h.saturating_mul(u32::try_from(rows).unwrap_or(1)),
        )
    }
}
