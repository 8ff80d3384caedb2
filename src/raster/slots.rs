//! A capacity-erased list: a borrowed slice of slots and the number in use.
//! Every table of the core is written against it, so the logic compiles
//! once per element type whatever the capacity, and the slots may live in
//! a fixed array (a microcontroller's static) or an ordinary `Vec` (the
//! host), as heapless' `VecView` erases the capacity of its `Vec`.

/// The first `len` slots of `items` are in use.
#[derive(Debug)]
pub(crate) struct Slots<'a, T> {
    items: &'a mut [T],
    len: &'a mut usize,
}

impl<'a, T: Copy> Slots<'a, T> {
    /// A list over `items`, of which the first `*len` are in use.
    pub fn new(items: &'a mut [T], len: &'a mut usize) -> Self {
        debug_assert!(*len <= items.len());
        Self { items, len }
    }

    /// Slots in use.
    pub fn len(&self) -> usize {
        *self.len
    }

    /// Slots in all.
    pub fn capacity(&self) -> usize {
        self.items.len()
    }

    /// Whether every slot is in use.
    pub fn is_full(&self) -> bool {
        *self.len == self.items.len()
    }

    /// Free slots.
    pub fn room(&self) -> usize {
        self.items.len() - *self.len
    }

    /// Appends `item`, or gives it back when full.
    #[inline]
    pub fn push(&mut self, item: T) -> Result<(), T> {
        match self.items.get_mut(*self.len) {
            Some(slot) => {
                *slot = item;
                *self.len += 1;
                Ok(())
            }
            None => Err(item),
        }
    }

    /// Keeps the first `len` items.
    pub fn truncate(&mut self, len: usize) {
        *self.len = (*self.len).min(len);
    }

    /// The items in use.
    pub fn as_slice(&self) -> &[T] {
        &self.items[..*self.len]
    }

    /// The items in use, mutably.
    pub fn as_mut_slice(&mut self) -> &mut [T] {
        &mut self.items[..*self.len]
    }

    /// Every slot, in use or not (scratch space for sorting).
    pub fn all_mut(&mut self) -> &mut [T] {
        self.items
    }

    /// Sets the number in use (at most the capacity).
    pub fn set_len(&mut self, len: usize) {
        *self.len = len.min(self.items.len());
    }
}

/// A capacity-erased table whose entries never move: the first `len`
/// entries of `order` name the slots in use, the rest the free ones, so
/// that removing an entry swaps two indices instead of copying the entry
/// (an active polygon is 128 bytes; on a Cortex-M0+ the copies of a
/// swap-remove took about 80,000 cycles a frame).
///
/// `order` stays a permutation of the slots: [`Self::new`] writes it, and
/// only swaps change it afterwards.
#[derive(Debug)]
pub(crate) struct OrderedSlots<'a, T> {
    items: &'a mut [T],
    order: &'a mut [u16],
    len: usize,
}

impl<'a, T: Copy> OrderedSlots<'a, T> {
    /// Most slots a table can index (its indices are `u16`).
    pub const MAX_SLOTS: usize = 1 << 16;

    /// An empty table over `items`, with `order` to index them (whatever
    /// it held is overwritten): as many slots as the shorter of the two,
    /// and at most [`Self::MAX_SLOTS`].
    pub fn new(items: &'a mut [T], order: &'a mut [u16]) -> Self {
        let slots = items.len().min(order.len()).min(Self::MAX_SLOTS);
        let order = &mut order[..slots];
        // slot < MAX_SLOTS = 2^16: the cast is exact. (Counting in a
        // `0u16..` range instead overflows on its 65,536th step.)
        for (slot, index) in order.iter_mut().enumerate() {
            *index = slot as u16;
        }
        Self {
            items: &mut items[..slots],
            order,
            len: 0,
        }
    }

    /// Entries in use.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Removes every entry.
    #[cfg(feature = "zbuffer")]
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// The slots in use, in table order.
    pub fn live_slots(&self) -> &[u16] {
        &self.order[..self.len]
    }

    /// The entry in `slot` (in use or not).
    pub fn get(&self, slot: usize) -> Option<&T> {
        self.items.get(slot)
    }

    /// The entry in `slot` (in use or not), mutably.
    pub fn get_mut(&mut self, slot: usize) -> Option<&mut T> {
        self.items.get_mut(slot)
    }

    /// The first entry in use, mutably.
    #[cfg(feature = "zbuffer")]
    pub fn first_mut(&mut self) -> Option<&mut T> {
        let slot = *self.live_slots().first()?;
        self.items.get_mut(usize::from(slot))
    }

    /// Adds an entry written by `fill` straight into a free slot (which
    /// holds an old entry or a filler until then) and returns the slot, or
    /// does nothing when full.
    #[inline]
    pub fn push_in_place(&mut self, fill: impl FnOnce(&mut T)) -> Result<usize, ()> {
        let slot = usize::from(*self.order.get(self.len).ok_or(())?);
        fill(self.items.get_mut(slot).ok_or(())?);
        self.len += 1;
        Ok(slot)
    }

    /// Adds `item` and returns its slot, or gives it back when full.
    pub fn push(&mut self, item: T) -> Result<usize, T> {
        self.push_in_place(|slot| *slot = item).map_err(|()| item)
    }

    /// The entries, the order array and the number in use, for a pass that
    /// removes entries as it goes: swapping two of the first `len` order
    /// entries, or lowering `len`, keeps the table valid.
    pub fn parts_mut(&mut self) -> (&mut [T], &mut [u16], &mut usize) {
        (&mut *self.items, &mut *self.order, &mut self.len)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::vec::Vec;

    /// The most slots a table can index, from longer storage: every slot
    /// numbered, with no overflow of the `u16` indices on the way.
    #[test]
    fn a_table_of_the_most_slots_numbers_them_all() {
        let mut items = std::vec![0u8; OrderedSlots::<u8>::MAX_SLOTS + 5];
        let mut order = std::vec![0u16; OrderedSlots::<u8>::MAX_SLOTS + 9];
        let mut slots = OrderedSlots::new(&mut items, &mut order);
        assert_eq!(slots.items.len(), OrderedSlots::<u8>::MAX_SLOTS);
        assert_eq!(slots.order.len(), OrderedSlots::<u8>::MAX_SLOTS);
        assert!(
            slots
                .order
                .iter()
                .enumerate()
                .all(|(k, &i)| usize::from(i) == k)
        );
        assert_eq!(slots.push(7), Ok(0));
    }

    /// Random pushes and removals against a model list: the live entries
    /// are always the model's, no entry moves, `order` stays a permutation
    /// of the slots, and a full table refuses a push.
    #[test]
    fn ordered_slots_keep_entries_in_place() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for capacity in [1usize, 2, 5, 17] {
            let mut items = [0u32; 17];
            // Garbage in the order array: `new` rewrites it.
            let mut order = [7u16; 20];
            let mut table = OrderedSlots::new(&mut items[..capacity], &mut order);
            let mut model: Vec<(usize, u32)> = Vec::new();
            for step in 0..2000u32 {
                if next() % 3 != 0 {
                    match table.push(step) {
                        Ok(slot) => model.push((slot, step)),
                        Err(back) => {
                            assert_eq!(back, step);
                            assert_eq!(model.len(), capacity);
                        }
                    }
                } else if !model.is_empty() {
                    let index = (next() % model.len() as u64) as usize;
                    let slot = usize::from(table.live_slots()[index]);
                    model.retain(|&(s, _)| s != slot);
                    let (_, order, len) = table.parts_mut();
                    *len -= 1;
                    order.swap(index, *len);
                }
                assert_eq!(table.len(), model.len());
                let mut live: Vec<_> = table
                    .live_slots()
                    .iter()
                    .map(|&s| (usize::from(s), *table.get(usize::from(s)).unwrap()))
                    .collect();
                live.sort();
                let mut expected = model.clone();
                expected.sort();
                assert_eq!(live, expected);
                let (_, order, _) = table.parts_mut();
                let mut seen = order.to_vec();
                seen.sort();
                assert!(seen.iter().copied().eq(0..capacity as u16));
            }
        }
    }
}
