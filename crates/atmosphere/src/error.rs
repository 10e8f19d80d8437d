//! The crate's error type: every bad input gets a typed error, nothing panics on user data.

/// What went wrong building or querying the atmosphere.
#[derive(Debug, thiserror::Error)]
pub enum AtmosphereError {
    /// A calendar date that does not exist (month 13, 30 February) or is outside the
    /// algorithm's supported years.
    #[error("invalid date {year:04}-{month:02}-{day:02}: {reason}")]
    InvalidDate { year: i32, month: u32, day: u32, reason: &'static str },
    /// A time of day that is not a finite number of hours within a year of the date.
    #[error("invalid UTC time {0} h: must be finite and within 8784 h (366 days) of the date")]
    InvalidTime(f64),
    /// A latitude outside [-90, 90] degrees or not finite.
    #[error("invalid latitude {0} deg: must be finite and within [-90, 90]")]
    InvalidLatitude(f64),
    /// A longitude outside [-360, 360] degrees or not finite.
    #[error("invalid longitude {0} deg: must be finite and within [-360, 360]")]
    InvalidLongitude(f64),
    /// A physical parameter of the atmosphere that is negative, non-finite or inconsistent.
    #[error("invalid atmosphere parameter `{name}` = {value}: {reason}")]
    InvalidParameter { name: &'static str, value: f64, reason: &'static str },
    /// A quality setting (sample count, LUT or map size) that is zero or unreasonably large.
    #[error("invalid setting `{name}` = {value}: {reason}")]
    InvalidSetting { name: &'static str, value: u64, reason: &'static str },
    /// A direction or position that is not finite or has zero length.
    #[error("invalid vector `{name}`: {reason}")]
    InvalidVector { name: &'static str, reason: &'static str },
    /// A built structure (LUT, sky map) whose invariants do not hold.
    #[error("invalid {what}: {reason}")]
    Invalid { what: &'static str, reason: String },
    /// The GPU path failed (no adapter, validation error, read-back failure).
    #[cfg(feature = "gpu")]
    #[error("atmosphere GPU path")]
    Gpu(#[from] gpu_harness::GpuError),
}
