//! The progressive build's state machine: the share of the loop over orders that each
//! frame records when the build is spread over frames ([`crate::Renderer::set_progressive`]).

/// A share of the loop over orders that one progressive frame records: order 1 (after
/// clearing S's multiple part and E, the sums of single scattering and their decision),
/// or part `part` of an order of two or more (0: Delta J's moments, Delta J and Delta E;
/// 1 to `slices`: Delta S slice `part - 1`, the last with the order's sums, decision and
/// accumulation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Share {
    pub order: u32,
    pub part: u32,
}

impl Share {
    /// The first share: single scattering's.
    pub const FIRST: Share = Share { order: 1, part: 0 };

    /// Whether this share ends its order: S and E then hold every order up to it.
    pub fn ends_order(self, slices: u32) -> bool {
        self.order == 1 || self.part == slices
    }

    /// The share after this one, `None` after the last order's last.
    pub fn after(self, slices: u32, max_orders: u32) -> Option<Share> {
        if !self.ends_order(slices) {
            Some(Share {
                part: self.part + 1,
                ..self
            })
        } else if self.order < max_orders {
            Some(Share {
                order: self.order + 1,
                part: 0,
            })
        } else {
            None
        }
    }

    /// What the share builds, for [`crate::frame::plan::FramePlan::building`].
    pub fn describe(self, slices: u32, max_orders: u32) -> String {
        match self.part {
            _ if self.order == 1 => "bruneton: single scattering".to_string(),
            0 => format!(
                "bruneton: order {} of at most {max_orders}, Delta J and Delta E",
                self.order
            ),
            p => format!(
                "bruneton: order {} of at most {max_orders}, Delta S slice {p} of {slices}",
                self.order
            ),
        }
    }
}

/// Which shares of the loop over orders a frame records.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Recording {
    /// All of it, in one frame.
    All,
    /// One share, of a build spread over frames.
    Share(Share),
}

impl Recording {
    /// Whether the frame records `share`.
    pub fn includes(self, share: Share) -> bool {
        match self {
            Recording::All => true,
            Recording::Share(s) => s == share,
        }
    }

    /// Whether the frame starts the loop: it clears S's multiple part and E first.
    pub fn starts(self) -> bool {
        self.includes(Share::FIRST)
    }
}

impl Recording {
    /// Whether the frame's share ends an order (`slices` Delta S slices per order): S
    /// and E then hold every order up to it, and the scattering textures are refreshed.
    pub fn ends_order(self, slices: u32) -> bool {
        match self {
            Recording::All => true,
            Recording::Share(s) => s.ends_order(slices),
        }
    }

    /// The share the next frame records, `None` when the build is complete.
    pub fn next(self, slices: u32, max_orders: u32) -> Option<Share> {
        match self {
            Recording::All => None,
            Recording::Share(s) => s.after(slices, max_orders),
        }
    }
}
