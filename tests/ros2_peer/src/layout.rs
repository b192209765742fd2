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

#[cfg(test)]
mod tests {
    use rustdds::serialization::deserialize_from_cdr_with_decoder_and_rep_id;
    use rustdds::RepresentationIdentifier;

    use super::*;
    use crate::messages::{Range, RangeLayout};

    /// A `Range` as CDR (little-endian, the payload after its encapsulation header), stamped
    /// 1 ns, frame `ps0`, range 0.05 m; Jazzy's carries a variance of 0.
    fn range_payload(with_variance: bool) -> Vec<u8> {
        let mut bytes = Vec::new();
        bytes.extend(0i32.to_le_bytes());
        bytes.extend(1u32.to_le_bytes());
        bytes.extend(4u32.to_le_bytes());
        bytes.extend(b"ps0\0");
        bytes.extend([1, 0, 0, 0]); // radiation_type, then padding to float32's alignment
        for value in [0.1f32, 0.005, 0.07, 0.05] {
            bytes.extend(value.to_le_bytes());
        }
        if with_variance {
            bytes.extend(0f32.to_le_bytes());
        }
        bytes
    }

    fn decode(bytes: &[u8], with_variance: bool) -> Result<Range, String> {
        let seed = WholePayload(RangeLayout { with_variance });
        deserialize_from_cdr_with_decoder_and_rep_id(bytes, RepresentationIdentifier::CDR_LE, seed)
            .map(|(range, _)| range)
            .map_err(|error| error.to_string())
    }

    #[test]
    fn each_distribution_reads_its_own_range() {
        let humble = decode(&range_payload(false), false).unwrap();
        assert_eq!(
            (
                humble.header.frame_id.as_str(),
                humble.range,
                humble.variance
            ),
            ("ps0", 0.05, None)
        );
        assert_eq!(humble.header.stamp.nanosec, 1);
        let jazzy = decode(&range_payload(true), true).unwrap();
        assert_eq!((jazzy.range, jazzy.variance), (0.05, Some(0.0)));
    }

    #[test]
    fn humble_reading_jazzy_range_is_a_mismatch() {
        let error = decode(&range_payload(true), false).unwrap_err();
        assert!(error.contains("fields this layout lacks"), "{error}");
    }

    #[test]
    fn jazzy_reading_humble_range_is_a_mismatch() {
        assert!(decode(&range_payload(false), true).is_err());
    }

    #[test]
    fn padding_to_four_bytes_is_not_a_field() {
        let mut padded = range_payload(false);
        padded.extend([0, 0, 0]);
        assert!(decode(&padded, false).is_ok());
    }
}
