//! Verification cases for dcfm.
