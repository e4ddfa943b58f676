//! Intensity measures of a motion: peaks ([`peaks`]), the elastic response spectrum by the
//! Nigam–Jennings recursion ([`spectrum`]), Arias intensity, the Husid curve and the
//! significant duration ([`arias`]), and the Fourier amplitude spectrum ([`fourier`]).

pub mod arias;
pub mod fourier;
pub mod peaks;
pub mod spectrum;

pub use arias::{arias_intensity, husid, significant_duration};
pub use fourier::fourier_amplitude;
pub use peaks::{peak, Peak};
pub use spectrum::{response_spectrum, sdof_response, SdofCoefficients, SpectrumPoint};
