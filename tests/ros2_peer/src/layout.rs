//! Decoding that insists the message fills its payload: CDR carries no field names, so a reader
//! whose layout lacks a field the writer sent (Humble's `Range` reading Jazzy's) would otherwise
//! decode the known prefix and silently drop the rest. [`WholePayload`] decodes the message,
//! then tries to read four more bytes: success means the writer's layout is longer than ours.
//! CDR pads a payload to a multiple of four bytes, so up to three trailing bytes are padding.
//! A writer's layout that is shorter than ours fails on its own (the payload ends early).

use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, DeserializeSeed, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer};

/// Decodes `S`'s value and fails when the payload holds four or more bytes after it.
#[derive(Clone, Copy, Debug)]
pub struct WholePayload<S>(pub S);

/// The seed of a type that needs none: `WholePayload(Plain::<LaserScan>::new())`.
pub struct Plain<T>(PhantomData<fn() -> T>);

impl<T> Plain<T> {
    pub fn new() -> Self {
        Plain(PhantomData)
    }
}

impl<T> Clone for Plain<T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for Plain<T> {}

impl<'de, T: Deserialize<'de>> DeserializeSeed<'de> for Plain<T> {
    type Value = T;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<T, D::Error> {
        T::deserialize(deserializer)
    }
}

/// The message, then whatever follows it, read as one sequence of unbounded length.
const UNBOUNDED: usize = usize::MAX;

impl<'de, S: DeserializeSeed<'de>> DeserializeSeed<'de> for WholePayload<S> {
    type Value = S::Value;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<S::Value, D::Error> {
        deserializer.deserialize_tuple(UNBOUNDED, self)
    }
}

impl<'de, S: DeserializeSeed<'de>> Visitor<'de> for WholePayload<S> {
    type Value = S::Value;

    fn expecting(&self, formatter: &mut fmt::Formatter) -> fmt::Result {
        formatter.write_str("a message that fills its payload")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<S::Value, A::Error> {
        let message = seq
            .next_element_seed(self.0)?
            .ok_or_else(|| de::Error::custom("the payload holds no message"))?;
        match seq.next_element::<[u8; 4]>() {
            Ok(Some(extra)) => Err(de::Error::custom(format!(
                "the payload goes on after the expected layout ends (next bytes {extra:02x?}): \
                 the writer's message has fields this layout lacks"
            ))),
            // The payload ended within the last four bytes: padding at most.
            Ok(None) | Err(_) => Ok(message),
        }
    }
}
