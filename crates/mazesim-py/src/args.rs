//! Integer arguments (counts, seeds, indices) taken as any Python object, so that one too large or
//! negative for its Rust type, or not an int at all, is an `InvalidArgumentError` naming the
//! argument and its range, not pyo3's `OverflowError` or `TypeError`.

use pyo3::prelude::*;
use pyo3::types::PyInt;

use crate::errors::{invalid, wrong_type, IntoPy};

/// An integer argument as given, checked against its range by [`IntArg::within`].
#[derive(Debug, Clone)]
pub enum IntArg {
    /// An int that fits in an `i128`.
    Int(i128),
    /// An int beyond `i128`, described for the error ("an int of 40 digits").
    Huge(String),
    /// Not an int: its type, described for the error.
    Other(String),
}

impl IntArg {
    /// The default of the seeds and thread counts.
    pub const ZERO: IntArg = IntArg::Int(0);

    /// The value as a `T` in `least..=most`; `name` names the argument in the error.
    pub fn within<T>(&self, name: &str, least: T, most: T) -> PyResult<T>
    where
        T: TryFrom<i128> + Into<i128> + Copy + std::fmt::Display,
    {
        let refuse = |found: String| {
            invalid(format!(
                "expected {name} to be an int in {least}..={most}, found {found}"
            ))
        };
        match self {
            IntArg::Int(v) if (least.into()..=most.into()).contains(v) => {
                T::try_from(*v).map_err(|_| refuse(v.to_string()))
            }
            IntArg::Int(v) => Err(refuse(v.to_string())),
            IntArg::Huge(found) => Err(refuse(found.clone())),
            IntArg::Other(found) => Err(wrong_type(format!(
                "expected {name} to be an int in {least}..={most}, found {found}"
            ))),
        }
    }

    /// A seed: an int in `0..2**64`.
    pub fn seed(&self, name: &str) -> PyResult<u64> {
        self.within(name, 0, u64::MAX)
    }

    /// A count or index in `0..=most`.
    pub fn count(&self, name: &str, most: usize) -> PyResult<usize> {
        let most = u64::try_from(most).unwrap_or(u64::MAX);
        self.within(name, 0u64, most).map(|v| v as usize)
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for IntArg {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        // True and False are ints to Python, not counts, seeds or indices: `num_envs=True` made
        // one environment (the Python side's check refuses a bool for an int too).
        if obj.is_instance_of::<pyo3::types::PyBool>() {
            return Ok(IntArg::Other(type_name(&obj)));
        }
        // Most ints fit 64 bits, read in one C call; pyo3 reads an i128 with Python arithmetic.
        if let Ok(v) = obj.extract::<i64>() {
            return Ok(IntArg::Int(i128::from(v)));
        }
        if let Ok(v) = obj.extract::<i128>() {
            return Ok(IntArg::Int(v));
        }
        if obj.is_instance_of::<PyInt>() {
            let digits = obj.str().map(|s| s.to_string()).unwrap_or_default();
            return Ok(IntArg::Huge(format!("an int of {} digits", digits.len())));
        }
        Ok(IntArg::Other(type_name(&obj)))
    }
}

/// A real-number argument as given: a float, or an int of any size (one beyond `f64` becomes an
/// infinity of its sign, which every check of a real refuses with its range), or something else,
/// described for the error by [`Real::value`].
#[derive(Debug, Clone)]
pub enum Real {
    /// A number.
    Number(f64),
    /// Not a number: its type's name.
    Other(String),
}

impl Real {
    /// The number; `name` names the argument in the error when it is not one.
    pub fn value(&self, name: &str) -> PyResult<f64> {
        match self {
            Real::Number(v) => Ok(*v),
            Real::Other(kind) => Err(wrong_type(format!(
                "expected {name} to be a real number, found {kind}"
            ))),
        }
    }

    /// The number as a coordinate of a point of a world (metres): finite and within
    /// `limits::MAX_COORDINATE`, as every pose and wall is. The one check of a point a query
    /// is asked about (a floor reading, a goal), so no query answers for NaN or 1e300.
    pub fn coordinate(&self, name: &str) -> PyResult<f64> {
        let value = self.value(name)?;
        mazesim_core::limits::check_bounded(
            &format!("{name} (metres)"),
            value,
            mazesim_core::limits::MAX_COORDINATE,
        )
        .py()?;
        Ok(value)
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Real {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        // True and False are ints to Python, not wheel speeds or volts to mazesim (a `step(True)`
        // would drive at 1 rad/s): refused as the Python side refuses them.
        if class_name(&obj) == "bool" {
            return Ok(Real::Other(type_name(&obj)));
        }
        // A complex number is not a real one, even when numpy's would convert (dropping its
        // imaginary part with a warning only): a numpy complex scalar or 0-d array is refused as
        // Python's own `complex` is.
        if is_complex(&obj) {
            return Ok(Real::Other(type_name(&obj)));
        }
        if let Ok(v) = obj.extract::<f64>() {
            return Ok(Real::Number(v));
        }
        if obj.is_instance_of::<PyInt>() {
            let negative = obj.lt(0).unwrap_or(false);
            return Ok(Real::Number(if negative {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            }));
        }
        let kind = type_name(&obj);
        Ok(Real::Other(kind))
    }
}

/// Whether `obj` is a complex number: Python's `complex` (numpy's `complex128` is one), or a
/// numpy scalar or array whose dtype is of the complex kind. Only numpy's own objects are asked
/// their dtype, so no other object's attribute code runs here.
fn is_complex(obj: &Bound<'_, PyAny>) -> bool {
    if obj.is_instance_of::<pyo3::types::PyComplex>() {
        return true;
    }
    let from_numpy = obj
        .get_type()
        .module()
        .map(|m| m.to_string().starts_with("numpy"))
        .unwrap_or(false);
    from_numpy
        && obj
            .getattr("dtype")
            .and_then(|d| d.getattr("kind"))
            .map(|k| k.to_string() == "c")
            .unwrap_or(false)
}

/// An argument of a plain Python type (a str, bool, path or list of str) taken as any Python
/// object, so that one of another type is an `InvalidArgumentError` naming the argument and the
/// type expected, not pyo3's `TypeError`.
#[derive(Debug, Clone)]
pub enum Given<T> {
    /// The value, of the expected type.
    Value(T),
    /// Not of the expected type: the name of the type found.
    Other(String),
}

impl<T> Given<T> {
    /// The value; `name` names the argument and `expected` its type in the error.
    pub fn value(self, name: &str, expected: &str) -> PyResult<T> {
        match self {
            Given::Value(v) => Ok(v),
            Given::Other(kind) => Err(wrong_type(format!(
                "expected {name} to be {expected}, found {kind}"
            ))),
        }
    }
}

impl<'a, 'py, T> FromPyObject<'a, 'py> for Given<T>
where
    T: FromPyObject<'a, 'py>,
{
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(v) = obj.extract::<T>() {
            return Ok(Given::Value(v));
        }
        let kind = type_name(&obj);
        Ok(Given::Other(kind))
    }
}

/// A text argument.
pub type Text = Given<String>;
/// A true/false argument (a bool or a numpy bool).
pub type Flag = Given<bool>;
/// A file path argument (a str or an `os.PathLike`).
pub type PathArg = Given<std::path::PathBuf>;

/// The contents of a `bytes` object (or a `bytearray`).
#[derive(Debug, Clone)]
pub struct ByteString(pub Vec<u8>);

impl<'a, 'py> FromPyObject<'a, 'py> for ByteString {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(bytes) = obj.cast::<pyo3::types::PyBytes>() {
            return Ok(ByteString(bytes.as_bytes().to_vec()));
        }
        let array = obj.cast::<pyo3::types::PyByteArray>()?;
        Ok(ByteString(array.to_vec()))
    }
}

/// A bytes argument.
pub type Bytes = Given<ByteString>;

/// A name shown in messages (the file a text came from): a str taken whole, any character that
/// is not Unicode text (the undecodable bytes of a file name, kept as surrogates by Python)
/// shown as U+FFFD.
#[derive(Debug, Clone)]
pub struct Label(pub String);

impl<'a, 'py> FromPyObject<'a, 'py> for Label {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let text = obj.cast::<pyo3::types::PyString>()?;
        if let Ok(plain) = text.to_cow() {
            return Ok(Label(plain.into_owned()));
        }
        // The bytes of the file name as the system gave them, each undecodable one shown once.
        let bytes = text.call_method1("encode", ("utf-8", "surrogateescape"));
        Ok(Label(
            match bytes.as_ref().map(|b| b.cast::<pyo3::types::PyBytes>()) {
                Ok(Ok(bytes)) => String::from_utf8_lossy(bytes.as_bytes()).into_owned(),
                _ => text.to_string_lossy().into_owned(),
            },
        ))
    }
}

/// A source-name argument (`source="maze.toml"`).
pub type SourceName = Given<Label>;

/// The name of an object's type as its `repr` shows it (`ndarray`, `NoneType`).
pub fn class_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_default()
}

/// What was found, for an error saying "expected ..., found {type_name}": the name of the
/// object's type with its article, as a Python user reads it ("an int", "a str", "an ndarray",
/// "None"); the one wording of the package's refusals of a type, which the Python side
/// (`mazesim.errors._a_type`) shares. A str that is not Unicode text (a byte of a file name or
/// command-line argument Python could not decode, kept as a lone surrogate) says so, since
/// "expected a str, found a str" would tell nothing.
pub fn type_name(obj: &Bound<'_, PyAny>) -> String {
    if obj.is_none() {
        return "None".into();
    }
    let name = with_article(&class_name(obj));
    match obj.cast::<pyo3::types::PyString>() {
        Ok(text) if text.to_cow().is_err() => format!(
            "{name} {NOT_UNICODE} (it holds a lone surrogate, as Python keeps a byte of a file \
             name or command-line argument it could not decode)"
        ),
        _ => name,
    }
}

/// `name` with "a" or "an" as it is spoken: "an int", "an ndarray", "a uint8", "a float".
pub fn with_article(name: &str) -> String {
    let lower = name.to_ascii_lowercase();
    // A "u" spoken "you" (uint8, unicode, UUID) takes "a".
    let spoken_you = ["uint", "uni", "uu", "use", "usu", "uti"]
        .iter()
        .any(|p| lower.starts_with(p));
    // An "nd" is spoken "en-dee" (ndarray).
    let vowel =
        (lower.starts_with(['a', 'e', 'i', 'o', 'u']) && !spoken_you) || lower.starts_with("nd");
    format!("{} {name}", if vowel { "an" } else { "a" })
}

/// What [`type_name`] says of a str that is not Unicode text: a str of the wrong value, not of
/// the wrong type, so the refusal of a wrong type (`wrong_type` in `errors.rs`) makes it an
/// `InvalidArgumentError`.
pub const NOT_UNICODE: &str = "that is not Unicode text";

/// The items of a sequence argument (a list, tuple, range or other sized iterable; not a str or
/// bytes), its `len()` checked against `most` BEFORE anything is reserved: every sequence taken
/// from Python goes through here, so that `seeds=range(10**9)` is an `InvalidArgumentError`
/// saying the bound and the length found, not an attempt to allocate for a billion items.
/// `expected` says what the items should be ("ints in 0..2**64"); an iterator that yields more
/// than its `len()` said is cut at `most` too.
pub fn bounded_items<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
    expected: &str,
    most: usize,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let message = |found: String| {
        format!("expected {name} to be a sequence of at most {most} {expected}, found {found}")
    };
    let refuse = |found: String| invalid(message(found));
    let textual = obj.is_instance_of::<pyo3::types::PyString>()
        || obj.is_instance_of::<pyo3::types::PyBytes>()
        || obj.is_instance_of::<pyo3::types::PyByteArray>();
    let len = match obj.len() {
        Ok(len) if !textual => len,
        // A length beyond `sys.maxsize`: a sequence, far too long.
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(obj.py()) => {
            return Err(refuse(format!(
                "{} of more than {most} items",
                type_name(obj)
            )))
        }
        // Text, or no length: not a sequence.
        _ => return Err(wrong_type(message(type_name(obj)))),
    };
    if len > most {
        return Err(refuse(format!("{} of {len} items", type_name(obj))));
    }
    let mut items = Vec::with_capacity(len);
    let iter = obj.try_iter().map_err(|_| {
        wrong_type(message(format!(
            "{} that cannot be iterated",
            type_name(obj)
        )))
    })?;
    for item in iter {
        if items.len() == most {
            return Err(refuse(format!(
                "{} of more than {most} items",
                type_name(obj)
            )));
        }
        items.push(item.map_err(|e| not_ours(obj.py(), e, name))?);
    }
    Ok(items)
}

/// An error raised by the user's own code while an argument was read (its `__iter__`, a
/// property): KeyboardInterrupt and the package's errors as they are, anything else as an
/// `InvalidArgumentError` naming the argument and carrying the original as its cause.
pub fn not_ours(py: Python<'_>, error: PyErr, name: &str) -> PyErr {
    let ours = py
        .import("mazesim.errors")
        .and_then(|m| m.getattr("MazesimError"))
        .is_ok_and(|root| error.is_instance(py, &root));
    if ours || !error.is_instance_of::<pyo3::exceptions::PyException>(py) {
        return error;
    }
    let wrapped = invalid(format!("reading {name} failed: {error}"));
    wrapped.set_cause(py, Some(error));
    wrapped
}

/// Most dimensions of a shape (numpy's own limit is 64).
pub const MOST_DIMENSIONS: usize = 64;

/// The `.shape` of an array-like argument as sizes, or `None` when it has none that is a short
/// sequence of ints (a shape of more than [`MOST_DIMENSIONS`] entries, `range(10**9)`, is not
/// read item by item).
pub fn shape_of(obj: &Bound<'_, PyAny>) -> Option<Vec<usize>> {
    let shape = obj.getattr("shape").ok()?;
    let items = bounded_items(&shape, "shape", "sizes", MOST_DIMENSIONS).ok()?;
    items.iter().map(|d| d.extract::<usize>().ok()).collect()
}

/// The error of calling a class that is made by its factories, `how` naming them.
pub fn made_elsewhere(class: &str, how: &str) -> PyErr {
    invalid(format!(
        "expected a {class} to be made by {how}, not by calling mazesim.{class}()"
    ))
}

/// `obj` as a `T`, else the error that the argument `name` was expected to be `what` ("a
/// TaskFeatures", "a RunSettings or None").
pub fn typed_argument<'a, 'py, T: pyo3::type_object::PyTypeCheck>(
    obj: &'a Bound<'py, PyAny>,
    name: &str,
    what: &str,
) -> PyResult<&'a Bound<'py, T>> {
    obj.cast::<T>().map_err(|_| {
        wrong_type(format!(
            "expected {name} to be {what}, found {}",
            type_name(obj)
        ))
    })
}

/// `obj` as a dict; `name` names the argument and `holding` says what it maps (" of name -> array").
pub fn dict_argument<'a, 'py>(
    obj: &'a Bound<'py, PyAny>,
    name: &str,
    holding: &str,
) -> PyResult<&'a Bound<'py, pyo3::types::PyDict>> {
    typed_argument(obj, name, &format!("a dict{holding}"))
}

/// The first key of `dict` that is not among `known` (names separated by white space), if any.
pub fn unknown_key(dict: &Bound<'_, pyo3::types::PyDict>, known: &str) -> PyResult<Option<String>> {
    for key in dict.keys() {
        let key = key.str()?.to_string();
        if !known.split_whitespace().any(|name| name == key) {
            return Ok(Some(key));
        }
    }
    Ok(None)
}

/// The keyword arguments of a call taken as `**options` and read once into the typed settings of
/// the core (`RunOptions`, `Perturbation`, `MazeParams`...), so a Rust function stays narrow
/// whatever the number of keywords its Python signature documents. A keyword the function does
/// not know is a `TypeError`, as Python says of any other function.
pub struct Keywords<'py> {
    given: Option<Bound<'py, pyo3::types::PyDict>>,
    function: &'static str,
}

impl<'py> Keywords<'py> {
    /// The keywords of `function`, each among `known` (names separated by white space).
    pub fn new(
        given: Option<&Bound<'py, pyo3::types::PyDict>>,
        function: &'static str,
        known: &str,
    ) -> PyResult<Self> {
        if let Some(key) = given.map(|g| unknown_key(g, known)).transpose()?.flatten() {
            return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "{function}() got an unexpected keyword argument '{key}'"
            )));
        }
        Ok(Self {
            given: given.cloned(),
            function,
        })
    }

    /// The value of `key` as a `T` (the argument types above take anything, `None` included),
    /// or `default` when it was not given.
    pub fn get<T>(&self, key: &str, default: T) -> PyResult<T>
    where
        T: for<'a> FromPyObject<'a, 'py>,
        for<'a> <T as FromPyObject<'a, 'py>>::Error: Into<PyErr>,
    {
        match self.item(key)? {
            Some(value) => value.extract::<T>().map_err(Into::into),
            None => Ok(default),
        }
    }

    /// The object given for `key`; `None` when it was not given or was `None`.
    pub fn object(&self, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        Ok(self.item(key)?.filter(|v| !v.is_none()))
    }

    /// The object given for `key`, which the call needs.
    pub fn required(&self, key: &str) -> PyResult<Bound<'py, PyAny>> {
        self.item(key)?.ok_or_else(|| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "{}() missing required keyword argument: '{key}'",
                self.function
            ))
        })
    }

    fn item(&self, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        match &self.given {
            Some(given) => given.get_item(key),
            None => Ok(None),
        }
    }
}

/// Warns (`DeprecationWarning`, at the caller's line) that a former way of calling is going.
pub fn warn_deprecated(py: Python<'_>, message: String) -> PyResult<()> {
    let message = std::ffi::CString::new(message).map_err(|e| invalid(e.to_string()))?;
    PyErr::warn(
        py,
        &py.get_type::<pyo3::exceptions::PyDeprecationWarning>(),
        &message,
        1,
    )
}
