//! The sections of a problem file that belong to its model (`[material]`, `[hinge]`, ...):
//! each model reads and validates its own through [`Sections`], with the same error
//! messages as the rest of the file.

use std::marker::PhantomData;

use serde::de::{DeserializeOwned, DeserializeSeed, IgnoredAny, MapAccess, Visitor};

use super::error::{Locator, Segment};
use super::reader::{deserialize, k, Reader, Res};
use super::ProblemError;

/// The model's view of a problem file: its sections, deserialized on request, and the
/// checks of single values.
pub struct Sections<'a, 'b> {
    reader: Reader<'a, 'b>,
    text: &'b str,
    model: &'static str,
}

impl<'a, 'b> Sections<'a, 'b> {
    pub(crate) fn new(loc: &'a Locator<'b>, text: &'b str, model: &'static str) -> Self {
        Sections {
            reader: Reader { loc },
            text,
            model,
        }
    }

    /// The top-level table `name` as `T`, `None` when the file has none.
    pub fn optional<T: DeserializeOwned>(&self, name: &str) -> Res<Option<T>> {
        deserialize(
            self.reader.loc,
            self.text,
            Pick::<T> {
                name,
                found: PhantomData,
            },
        )
    }

    /// The top-level table `name` as `T`, which the model needs.
    pub fn required<T: DeserializeOwned>(&self, name: &str) -> Res<T> {
        self.optional(name)?.ok_or_else(|| self.missing(name))
    }

    /// The error for a section the model needs and the file lacks.
    pub fn missing(&self, name: &str) -> ProblemError {
        self.reader.err(
            &[k(name)],
            format!("missing field `{name}`: the {} model needs it", self.model),
        )
    }

    /// An error at the key `path`.
    pub fn err(&self, path: &[Segment], message: impl Into<String>) -> ProblemError {
        self.reader.err(path, message)
    }
}

impl<'a, 'b> std::ops::Deref for Sections<'a, 'b> {
    type Target = Reader<'a, 'b>;

    fn deref(&self) -> &Self::Target {
        &self.reader
    }
}

/// Deserializes the one top-level entry `name` of a document, passing over the others.
struct Pick<'n, T> {
    name: &'n str,
    found: PhantomData<T>,
}

impl<'de, T: DeserializeOwned> DeserializeSeed<'de> for Pick<'_, T> {
    type Value = Option<T>;

    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de, T: DeserializeOwned> Visitor<'de> for Pick<'_, T> {
    type Value = Option<T>;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "a problem file")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut found = None;
        while let Some(key) = map.next_key::<String>()? {
            if key == self.name {
                found = Some(map.next_value::<T>()?);
            } else {
                map.next_value::<IgnoredAny>()?;
            }
        }
        Ok(found)
    }
}
