//! Bytes held on the heap by worlds and simulators, as their structures account for them, for
//! reporting the memory a batch needs per env (`Batch::bytes_per_env`). The counts are of the
//! allocations' sizes, not of the allocator's own overhead.

/// Heap bytes of a vector's buffer.
pub fn vec_bytes<T>(v: &Vec<T>) -> usize {
    v.capacity() * std::mem::size_of::<T>()
}

/// Heap bytes of a string's buffer.
pub fn string_bytes(s: &str) -> usize {
    s.len()
}
