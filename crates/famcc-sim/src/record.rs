//! What a run keeps of every sample ([`Record`]).

use crate::control::Diag;

/// How much of the controllers' diagnostics a [`Record`] keeps per sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Detail {
    /// None.
    None,
    /// [`CAMPAIGN_COLUMNS`]: what a campaign's criteria need.
    Campaign,
    /// [`FULL_COLUMNS`] and the estimate `z_hat_1 .. z_hat_n`.
    Full,
}

/// The diagnostics columns of [`Detail::Full`], before the estimate's.
pub const FULL_COLUMNS: [&str; 11] = [
    "xi",
    "xi_nominal",
    "expansion",
    "s",
    "s_prev",
    "ds_prev",
    "bound_x",
    "bound_y",
    "nominal_bound_x",
    "nominal_bound_y",
    "expanded",
];

/// The diagnostics columns of [`Detail::Campaign`].
pub const CAMPAIGN_COLUMNS: [&str; 2] = ["xi_nominal", "expansion"];

/// The samples of a run (or of one block of it), row by row. Per-sample
/// columns hold `channels * lanes` values per row (channel-major), `x`
/// `states * lanes`, `diag` `channels * lanes * width` with `width` the
/// number of diagnostics columns. A lane that has stopped records NaN.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// Which diagnostics are kept.
    pub detail: Detail,
    /// Whether the states are kept.
    pub keep_states: bool,
    /// Rows recorded.
    pub rows: usize,
    /// The true error `y - y_d`.
    pub e: Vec<f64>,
    /// The error the controller was given (noise included).
    pub e_measured: Vec<f64>,
    /// The controller's output.
    pub v: Vec<f64>,
    /// The applied input `clip(v)`.
    pub u: Vec<f64>,
    /// The input disturbance.
    pub d: Vec<f64>,
    /// The plant's states at the sample.
    pub x: Vec<f64>,
    /// The diagnostics, `width` per channel and lane.
    pub diag: Vec<f64>,
    /// Diagnostics columns per channel and lane (0 until the first row).
    pub width: usize,
}

impl Record {
    /// An empty record.
    pub fn new(detail: Detail, keep_states: bool) -> Self {
        Self {
            detail,
            keep_states,
            rows: 0,
            e: Vec::new(),
            e_measured: Vec::new(),
            v: Vec::new(),
            u: Vec::new(),
            d: Vec::new(),
            x: Vec::new(),
            diag: Vec::new(),
            width: 0,
        }
    }

    /// The diagnostics columns per channel and lane for a controller of order `n`.
    pub fn width_for(&self, n: usize) -> usize {
        match self.detail {
            Detail::None => 0,
            Detail::Campaign => CAMPAIGN_COLUMNS.len(),
            Detail::Full => FULL_COLUMNS.len() + n,
        }
    }

    /// Appends one controller's diagnostics (NaN for `None`) in `n` columns' layout.
    pub(crate) fn push_diag(&mut self, d: Option<&Diag>, n: usize) {
        let unknown = Diag::unknown(n);
        let d = d.unwrap_or(&unknown);
        match self.detail {
            Detail::None => {}
            Detail::Campaign => self.diag.extend_from_slice(&[d.xi_nominal, d.expansion]),
            Detail::Full => {
                let expanded = f64::from(u8::from(d.expanded));
                self.diag.extend_from_slice(&[
                    d.xi,
                    d.xi_nominal,
                    d.expansion,
                    d.s,
                    d.s_prev,
                    d.ds_prev,
                    d.bounds[0],
                    d.bounds[1],
                    d.nominal_bounds[0],
                    d.nominal_bounds[1],
                    expanded,
                ]);
                self.diag
                    .extend((0..n).map(|i| d.z_hat.get(i).copied().unwrap_or(f64::NAN)));
            }
        }
    }
}
