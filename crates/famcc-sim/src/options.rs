//! What a run is ([`Options`]) and why a lane of it stopped ([`Stop`]).

/// The numbers of a run: the sample grid, the layout of lanes, channels and
/// states, the actuator limits and when a lane counts as diverged.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Sample period, s (finite, > 0).
    pub dt: f64,
    /// Samples of the whole run, `K >= 1` (times `k dt`, `k = 0..K`).
    pub samples: usize,
    /// RK4 steps per sample period (>= 1).
    pub substeps: usize,
    /// Independent copies of the closed loop (>= 1).
    pub lanes: usize,
    /// Plant states per lane (>= 1).
    pub states: usize,
    /// Per channel, the index of its output among a lane's states
    /// (`[0]` for a single-output plant; `[0, 2]` for a two-joint arm).
    pub outputs: Vec<usize>,
    /// Per channel, the actuator limits `(lo, hi)`, `lo < hi`, or None.
    pub limits: Vec<Option<(f64, f64)>>,
    /// A lane stops at the first sample with some `|e| > diverge_at` (true
    /// error, before the controller steps).
    pub diverge_at: Option<f64>,
    /// A lane stops when a state leaves `|x_i| <= state_bound`.
    pub state_bound: Option<f64>,
}

impl Options {
    /// One lane, one channel whose output is state 0.
    pub fn single(
        dt: f64,
        samples: usize,
        substeps: usize,
        states: usize,
        limits: Option<(f64, f64)>,
    ) -> Self {
        Self {
            dt,
            samples,
            substeps,
            lanes: 1,
            states,
            outputs: vec![0],
            limits: vec![limits],
            diverge_at: None,
            state_bound: None,
        }
    }

    /// The number of channels.
    pub fn channels(&self) -> usize {
        self.outputs.len()
    }

    /// Checks the options; the error names the field and the rule.
    pub fn check(&self) -> Result<(), &'static str> {
        let positive = |x: f64| x.is_finite() && x > 0.0;
        if !positive(self.dt) {
            return Err("dt must be finite and > 0");
        }
        if self.samples == 0 || self.substeps == 0 || self.lanes == 0 || self.states == 0 {
            return Err("samples, substeps, lanes and states must be >= 1");
        }
        if self.outputs.is_empty() || self.outputs.iter().any(|&i| i >= self.states) {
            return Err("outputs must name at least one channel, each a state index < states");
        }
        if self.limits.len() != self.outputs.len() {
            return Err("limits must have one entry (or None) per channel");
        }
        if self
            .limits
            .iter()
            .flatten()
            .any(|&(lo, hi)| lo.partial_cmp(&hi) != Some(core::cmp::Ordering::Less))
        {
            return Err("limits must satisfy lo < hi");
        }
        if self.diverge_at.is_some_and(|b| !positive(b)) || self.state_bound.is_some_and(|b| !positive(b)) {
            return Err("diverge_at and state_bound must be finite and > 0");
        }
        Ok(())
    }
}

/// Why a lane stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reason {
    /// Some `|e| > diverge_at` at the sample (kept without a step: `v` NaN).
    Diverged,
    /// A controller returned a non-finite output (the sample is kept).
    NonFiniteOutput,
    /// The integration from the sample gave a non-finite state.
    NonFiniteState,
    /// The integration from the sample left `|x_i| <= state_bound`.
    StateBound,
    /// The plant's right-hand side failed integrating from the sample.
    PlantError,
}

impl Reason {
    /// A stable name: `"diverged"`, `"non-finite-output"`,
    /// `"non-finite-state"`, `"state-bound"`, `"plant-error"`.
    pub fn name(self) -> &'static str {
        match self {
            Reason::Diverged => "diverged",
            Reason::NonFiniteOutput => "non-finite-output",
            Reason::NonFiniteState => "non-finite-state",
            Reason::StateBound => "state-bound",
            Reason::PlantError => "plant-error",
        }
    }

    /// True when the last kept sample is partial: the controller did not
    /// step (diverged) or returned no usable output, so its diagnostics are
    /// not recorded.
    pub fn partial(self) -> bool {
        matches!(self, Reason::Diverged | Reason::NonFiniteOutput)
    }
}

/// Where and why a lane stopped: `samples` is the number of samples it
/// kept (the last kept one is `samples - 1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Stop {
    /// Samples kept.
    pub samples: usize,
    /// Why.
    pub reason: Reason,
}
