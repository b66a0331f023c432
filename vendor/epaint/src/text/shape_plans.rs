//! Vendored change: harfrust shape plans kept per font face.
//!
//! Upstream shaped every run of text without a plan, so harfrust made one for
//! each run (its features collected and its lookups compiled from the face's
//! tables), the larger part of shaping a short label. A plan depends only on
//! the face (and its variation instance), the run's direction, script and
//! language and the features asked for: kept here per face without
//! variations, for the runs' direction, script and language (no features are
//! asked for), the same plan harfrust would make for each run.

use alloc::sync::Arc;
use alloc::vec::Vec;

use crate::mutex::Mutex;

/// How many plans a face keeps (the last made, once there are more): a face
/// meets few scripts and directions.
const KEPT: usize = 8;

/// What a plan is made for: the run's direction, script and language.
type PlanKey = (harfrust::Direction, Option<harfrust::Script>, Option<harfrust::Language>);

/// A face's shape plans (for the face without variations).
#[derive(Default)]
pub(crate) struct ShapePlans(Mutex<Vec<(PlanKey, Arc<harfrust::ShapePlan>)>>);

impl ShapePlans {
    /// The plan for shaping `buffer` (its segment properties guessed, nothing
    /// set on it by hand) with `shaper`, the face without variations: the one
    /// made for an earlier run of the same direction, script and language, or
    /// a new one.
    pub(crate) fn plan(&self, shaper: &harfrust::Shaper<'_>, buffer: &harfrust::UnicodeBuffer) -> Arc<harfrust::ShapePlan> {
        // A guess leaves the script unset (not `UNKNOWN`) where it finds none.
        let script = Some(buffer.script()).filter(|s| *s != harfrust::script::UNKNOWN);
        let key: PlanKey = (buffer.direction(), script, buffer.language());
        let mut plans = self.0.lock();
        if let Some((_, plan)) = plans.iter().find(|(k, _)| *k == key) {
            return Arc::clone(plan);
        }
        let plan = Arc::new(harfrust::ShapePlan::new(shaper, key.0, key.1, key.2.as_ref(), &[]));
        if plans.len() == KEPT {
            plans.remove(0);
        }
        plans.push((key, Arc::clone(&plan)));
        plan
    }
}
