//! Shared by the integration tests and the accuracy table: the high-precision reference
//! cases of `tests/reference/cases.csv` and how mechgen's answers compare with them.

pub mod baselines;
pub mod batch_baseline;
pub mod examples;
pub mod kernels;
pub mod oracle;
pub mod reference;
pub mod scenes;
pub mod stamp;
