//! placeholder

use crate::record::CheckRow;

pub fn run() -> dcfm::Result<Vec<CheckRow>> {
    Ok(Vec::new())
}
