//! The undo log of ring roles: not in paper 000. The self-check changes the rings in place
//! (flips, corner switches) and gives them back to the ring cache as they were, without
//! copying the tables each round.

use crate::hex::classify::{Rings, Role};
use crate::hex::lattice::{FxHashMap, Key};

/// The roles the decisions of `RingState` replaced in a set of rings, oldest first (`true`
/// for `Rings::contested`, `false` for `Rings::roles`): undone in reverse, they give the
/// rings back as `RingCache` keeps them, without copying the tables each round.
#[derive(Default)]
pub(super) struct Undo(Vec<(bool, Key, Option<Role>)>);

impl Undo {
    fn table(r: &mut Rings, contested: bool) -> &mut FxHashMap<Key, Role> {
        if contested {
            &mut r.contested
        } else {
            &mut r.roles
        }
    }

    pub(super) fn set(&mut self, r: &mut Rings, contested: bool, key: Key, role: Role) {
        let old = Undo::table(r, contested).insert(key, role);
        self.0.push((contested, key, old));
    }

    pub(super) fn restore(self, r: &mut Rings) {
        for (contested, key, old) in self.0.into_iter().rev() {
            let map = Undo::table(r, contested);
            match old {
                Some(role) => map.insert(key, role),
                None => map.remove(&key),
            };
        }
    }
}
