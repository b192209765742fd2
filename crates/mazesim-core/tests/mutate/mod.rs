//! Byte mutations of a text or binary input, for the fuzz tests of the readers: flips,
//! truncations, insertions of a format's own syntax (`snippets`) or of random bytes, deletions and
//! duplications.

use proptest::prelude::*;
use proptest::sample::Index;

#[derive(Debug, Clone)]
pub enum Mutation {
    Flip(Index, u8),
    Truncate(Index),
    Insert(Index, usize),
    InsertBytes(Index, Vec<u8>),
    Delete(Index, usize),
    Duplicate(Index, usize, Index),
}

pub fn mutation(snippets: usize) -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Mutation::Flip(i, b)),
        any::<Index>().prop_map(Mutation::Truncate),
        (any::<Index>(), 0..snippets).prop_map(|(i, s)| Mutation::Insert(i, s)),
        (any::<Index>(), prop::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(i, b)| Mutation::InsertBytes(i, b)),
        (any::<Index>(), 1usize..64).prop_map(|(i, n)| Mutation::Delete(i, n)),
        (any::<Index>(), 1usize..400, any::<Index>())
            .prop_map(|(i, n, j)| Mutation::Duplicate(i, n, j)),
    ]
}

pub fn apply(bytes: &mut Vec<u8>, m: &Mutation, snippets: &[&str]) {
    let len = bytes.len();
    let at = |i: &Index| if len == 0 { 0 } else { i.index(len + 1) };
    match m {
        Mutation::Flip(i, b) if len > 0 => {
            let k = i.index(len);
            bytes[k] ^= b | 1;
        }
        Mutation::Flip(..) => {}
        Mutation::Truncate(i) => bytes.truncate(at(i)),
        Mutation::Insert(i, s) => {
            let k = at(i);
            bytes.splice(k..k, snippets[*s].bytes());
        }
        Mutation::InsertBytes(i, b) => {
            let k = at(i);
            bytes.splice(k..k, b.iter().copied());
        }
        Mutation::Delete(i, n) => {
            let k = at(i);
            bytes.drain(k..(k + n).min(len));
        }
        Mutation::Duplicate(i, n, j) => {
            let k = at(i);
            let piece: Vec<u8> = bytes[k..(k + n).min(len)].to_vec();
            let to = at(j);
            bytes.splice(to..to, piece);
        }
    }
}
