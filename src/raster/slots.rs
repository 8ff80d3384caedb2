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

    /// Appends an item written by `fill` straight into the next slot (which
    /// holds an old item or a filler until then), or does nothing when
    /// full.
    #[inline]
    pub fn push_in_place(&mut self, fill: impl FnOnce(&mut T)) -> Result<(), ()> {
        let slot = self.items.get_mut(*self.len).ok_or(())?;
        fill(slot);
        *self.len += 1;
        Ok(())
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
