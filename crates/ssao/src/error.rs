//! Typed errors: bad views and settings are named, never a panic.

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SsaoError {
    /// A matrix, position or direction was NaN or infinite, or a direction was zero.
    #[error("non-finite or degenerate input: {0}")]
    NonFinite(&'static str),
    /// A size or count out of range.
    #[error("invalid parameter `{name}`: {reason}")]
    InvalidParameter { name: &'static str, reason: String },
}
