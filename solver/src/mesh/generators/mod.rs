//! Parametric mesh generators of whole models: the underground powerhouse
//! ([`cavern`]) and its Yingxiuwan preset ([`yingxiuwan`]).

pub mod cavern;
pub mod yingxiuwan;
