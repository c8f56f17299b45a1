//! The library's one error type: what went wrong, as one line naming the input at fault and
//! the rule it breaks ("case.toml, line 4: \[layers\] growth = 0.9: must be > 1"), with its
//! [`ErrorKind`] for callers that react to the kind (the CLI's exit status, Python's
//! `FileNotFoundError`). Every stage's error is folded into that line where it is raised,
//! with what was being done in front ([`Context`]), so the message reads the same whoever
//! prints it.

use std::fmt::Display;

/// What kind of fault an [`Error`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ErrorKind {
    /// Bad input: a case, its geometry, a motion, an option (fix the input).
    Input,
    /// A file named by the input does not exist.
    NotFound,
    /// The system refused a read or a write (a folder that is not writable, a full disk).
    Io,
    /// The run was interrupted (Ctrl-C, SIGTERM); nothing was written.
    Interrupted,
}

/// Why a call failed, as one line.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct Error {
    kind: ErrorKind,
    message: String,
}

/// The library's result.
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// A bad-input error with this message.
    pub fn input(message: impl Into<String>) -> Error {
        Error {
            kind: ErrorKind::Input,
            message: message.into(),
        }
    }

    /// What kind of fault it is.
    pub fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// The one-line message (the same as its `Display`).
    pub fn message(&self) -> &str {
        &self.message
    }

    /// The error with `what` in front: "what: message".
    #[must_use]
    pub fn context(self, what: impl Display) -> Error {
        Error {
            kind: self.kind,
            message: format!("{what}: {}", self.message),
        }
    }

    /// An error of `kind` whose message is `e`'s display followed by its sources'.
    fn chained(kind: ErrorKind, e: &dyn std::error::Error) -> Error {
        let mut message = e.to_string();
        let mut source = e.source();
        while let Some(s) = source {
            // as `anyhow`'s alternate display: every source, even one its parent shows
            message.push_str(": ");
            message.push_str(&s.to_string());
            source = s.source();
        }
        Error { kind, message }
    }
}

impl From<std::io::Error> for Error {
    fn from(e: std::io::Error) -> Error {
        let kind = match e.kind() {
            std::io::ErrorKind::NotFound => ErrorKind::NotFound,
            _ => ErrorKind::Io,
        };
        Error::chained(kind, &e)
    }
}

impl From<mesh_io::IoError> for Error {
    fn from(e: mesh_io::IoError) -> Error {
        let kind = match &e {
            mesh_io::IoError::Io { source, .. }
                if source.kind() == std::io::ErrorKind::NotFound =>
            {
                ErrorKind::NotFound
            }
            mesh_io::IoError::Io { .. } => ErrorKind::Io,
            mesh_io::IoError::Interrupted { .. } => ErrorKind::Interrupted,
            _ => ErrorKind::Input,
        };
        Error::chained(kind, &e)
    }
}

/// Bad input from a parser or a stage: the error's text (and its sources').
macro_rules! input_from {
    ($($ty:ty),* $(,)?) => {$(
        impl From<$ty> for Error {
            fn from(e: $ty) -> Error {
                Error::chained(ErrorKind::Input, &e)
            }
        }
    )*};
}

input_from!(
    serde_json::Error,
    std::num::ParseFloatError,
    geom_curve::CurveError,
    jacobian_check::JacobianError,
);

/// Puts what was being done in front of an error, as `anyhow`'s context does ("what: why").
pub trait Context<T> {
    /// The error, if any, with `what` in front.
    fn context<C: Display>(self, what: C) -> Result<T>;
    /// The error, if any, with `what()` in front (made only on error).
    fn with_context<C: Display, F: FnOnce() -> C>(self, what: F) -> Result<T>;
}

impl<T, E: Into<Error>> Context<T> for std::result::Result<T, E> {
    fn context<C: Display>(self, what: C) -> Result<T> {
        self.map_err(|e| e.into().context(what))
    }
    fn with_context<C: Display, F: FnOnce() -> C>(self, what: F) -> Result<T> {
        self.map_err(|e| e.into().context(what()))
    }
}

impl<T> Context<T> for Option<T> {
    fn context<C: Display>(self, what: C) -> Result<T> {
        self.ok_or_else(|| Error::input(what.to_string()))
    }
    fn with_context<C: Display, F: FnOnce() -> C>(self, what: F) -> Result<T> {
        self.ok_or_else(|| Error::input(what().to_string()))
    }
}

/// A bad-input [`Error`] from a format string (or any displayable value).
macro_rules! input_error {
    ($msg:literal $(,)?) => { $crate::error::Error::input(format!($msg)) };
    ($fmt:literal, $($arg:tt)*) => { $crate::error::Error::input(format!($fmt, $($arg)*)) };
    ($err:expr $(,)?) => { $crate::error::Error::input($err.to_string()) };
}

/// Returns early with a bad-input [`Error`].
macro_rules! bail {
    ($($arg:tt)*) => { return Err($crate::error::input_error!($($arg)*)) };
}

/// Returns early with a bad-input [`Error`] unless the condition holds.
macro_rules! ensure {
    ($cond:expr, $($arg:tt)*) => {
        if !$cond {
            $crate::error::bail!($($arg)*);
        }
    };
}

pub(crate) use {bail, ensure, input_error};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn context_reads_outer_to_inner() {
        let e: Result<()> = Err(Error::input("must be > 1"));
        let e = e
            .context("[layers] growth")
            .context("case.toml")
            .unwrap_err();
        assert_eq!(e.to_string(), "case.toml: [layers] growth: must be > 1");
        assert_eq!(e.kind(), ErrorKind::Input);
    }

    #[test]
    fn a_missing_file_is_not_found() {
        let e = std::fs::read("/no/such/file").with_context(|| "cannot read x");
        let e = e.unwrap_err();
        assert_eq!(e.kind(), ErrorKind::NotFound);
        assert!(e.to_string().starts_with("cannot read x: "), "{e}");
    }
}
