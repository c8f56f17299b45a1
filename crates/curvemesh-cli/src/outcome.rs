//! How a command that did not fail on bad input ended: valid, or a mesh written that failed
//! validation (with the line that says so).

/// How a run that did not fail on bad input ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Everything was made and passed validation.
    Valid,
    /// A mesh was written, but it failed validation (named in the report).
    Invalid,
}

/// How a run ended, with the line for stderr when the mesh failed validation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Finished {
    /// Valid or not.
    pub outcome: Outcome,
    /// For [`Outcome::Invalid`]: what failed and where the report is, on one line.
    pub problem: Option<String>,
}

impl Finished {
    /// A valid run.
    pub fn valid() -> Finished {
        Finished {
            outcome: Outcome::Valid,
            problem: None,
        }
    }

    /// Valid, or invalid with `problem` (a report's [`curvemesh::Report::verdict`]).
    pub fn of(problem: Option<String>) -> Finished {
        match problem {
            None => Finished::valid(),
            Some(line) => Finished {
                outcome: Outcome::Invalid,
                problem: Some(line),
            },
        }
    }
}
