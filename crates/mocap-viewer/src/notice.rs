//! The message shown in the banner over the 3D view: what went wrong and what
//! became of what the user had open.

/// What a failure did to what was open, which decides the banner's wording.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Files were given and none of them opened: what was open stays.
    NothingOpened,
    /// Some of the files given opened (replacing or joining what was open, as asked);
    /// the message names the ones that did not.
    PartlyOpened,
    /// Something the user did (an edit, a key, a layer, a capture) was refused and
    /// nothing changed.
    Refused,
}

/// A message for the banner: the text (with file, line and column where they
/// apply) and what became of what was open.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Notice {
    /// What went wrong, one line per failure.
    pub message: String,
    /// What the failure did to what was open.
    pub outcome: Outcome,
}

impl Notice {
    /// A notice for files given to open, of which `opened_any` says whether any opened.
    pub fn open_failed(message: String, opened_any: bool) -> Self {
        let outcome = if opened_any { Outcome::PartlyOpened } else { Outcome::NothingOpened };
        Notice { message, outcome }
    }

    /// A notice for an action that was refused (nothing changed).
    pub fn refused(message: String) -> Self {
        Notice { message, outcome: Outcome::Refused }
    }

    /// The banner's bold first line.
    pub fn headline(&self) -> String {
        match self.outcome {
            Outcome::NothingOpened | Outcome::PartlyOpened => format!("Could not open file: {}", self.message),
            Outcome::Refused => format!("Could not do that: {}", self.message),
        }
    }

    /// The banner's second line, saying what became of what was open, given whether
    /// anything is open now; `None` when there is nothing to say.
    pub fn note(&self, anything_open: bool) -> Option<&'static str> {
        match self.outcome {
            Outcome::NothingOpened if anything_open => Some("What was open is still open."),
            Outcome::NothingOpened => None,
            Outcome::PartlyOpened => Some("The other files opened."),
            Outcome::Refused => Some("Nothing was changed."),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wording_follows_the_outcome() {
        let none = Notice::open_failed("a.bvh:3:1: bad".into(), false);
        assert_eq!(none.headline(), "Could not open file: a.bvh:3:1: bad");
        assert_eq!(none.note(true), Some("What was open is still open."));
        assert_eq!(none.note(false), None);
        let partly = Notice::open_failed("skin.jpg:byte 0: bad".into(), true);
        assert_eq!(partly.outcome, Outcome::PartlyOpened);
        assert_eq!(partly.note(true), Some("The other files opened."));
        let refused = Notice::refused("no key at frame 3".into());
        assert_eq!(refused.headline(), "Could not do that: no key at frame 3");
        assert_eq!(refused.note(true), Some("Nothing was changed."));
    }
}
