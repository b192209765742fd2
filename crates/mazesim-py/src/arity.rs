//! Wrong arguments to an entry point of `mazesim._core`: too many, a required one missing, an
//! unknown keyword. pyo3 refuses them with a bare `TypeError` before the entry point's body (and
//! its own checks) runs, and CPython does so itself for an entry point without parameters; such
//! a `TypeError` is outside `mazesim.MazesimError`. [`guard_module`], run once when the module is
//! made, makes every such refusal an `InvalidArgumentError` with the same message, for every
//! function, method, static and class method of the module and every class's constructor, so that
//! an entry point added later is covered without code of its own.
//!
//! How, without slowing a valid call: CPython calls a compiled function or method through its
//! `PyMethodDef`, whose C function it reads at each call. Each def is pointed at a trampoline of
//! its own ([`TRAMPOLINES`], one per def, from a fixed pool), which calls the original function
//! and, only when that failed with exactly `TypeError`, replaces the exception. A def without
//! parameters (`METH_NOARGS`, where CPython would refuse extra arguments before any of our code)
//! becomes a `METH_VARARGS | METH_KEYWORDS` def whose trampoline refuses any argument itself. A
//! class's constructor (its `tp_new` slot, not a def) gets a `__new__` that calls the original
//! slot the same way. The compiled bodies are untouched; a valid call pays one indirect call.
//!
//! The objects are read through the layouts of `PyMethodDescrObject` and `PyCFunctionObject`,
//! which CPython has kept unchanged since 3.8 (the oldest Python the package supports is 3.9).

use std::collections::HashSet;
use std::ffi::{c_char, c_void, CStr, CString};
use std::sync::atomic::{AtomicBool, AtomicPtr, AtomicUsize, Ordering};

use pyo3::ffi;
use pyo3::prelude::*;
use pyo3::types::{PyCFunction, PyDict, PyTuple, PyType};

use crate::args::with_article;
use crate::errors::{invalid, wrong_type};

/// The start of a method descriptor (CPython's `PyMethodDescrObject`, a method or class method).
#[repr(C)]
struct MethodDescriptor {
    ob_base: ffi::PyObject,
    d_type: *mut ffi::PyTypeObject,
    d_name: *mut ffi::PyObject,
    d_qualname: *mut ffi::PyObject,
    d_method: *mut ffi::PyMethodDef,
    vectorcall: *mut c_void,
}

/// The start of a built-in function (CPython's `PyCFunctionObject`: a module's function, the
/// function inside a static method).
#[repr(C)]
struct BuiltinFunction {
    ob_base: ffi::PyObject,
    m_ml: *mut ffi::PyMethodDef,
    m_self: *mut ffi::PyObject,
    m_module: *mut ffi::PyObject,
    m_weakreflist: *mut ffi::PyObject,
    vectorcall: *mut c_void,
}

/// One trampoline's target: the original C function, whether it takes no arguments, and the
/// entry point's name for the message.
struct Slot {
    original: AtomicPtr<c_void>,
    takes_none: AtomicBool,
    name: AtomicPtr<c_char>,
}

#[allow(clippy::declare_interior_mutable_const)] // copied into each element of SLOTS, never used
const EMPTY: Slot = Slot {
    original: AtomicPtr::new(std::ptr::null_mut()),
    takes_none: AtomicBool::new(false),
    name: AtomicPtr::new(std::ptr::null_mut()),
};

/// Trampolines available: more than the module's functions and methods (about 170); a module
/// that outgrows it fails to import with a message saying so (the tests import it).
const POOL: usize = 256;
static SLOTS: [Slot; POOL] = [EMPTY; POOL];
static USED: AtomicUsize = AtomicUsize::new(0);

type Trampoline = unsafe extern "C" fn(
    *mut ffi::PyObject,
    *mut ffi::PyObject,
    *mut ffi::PyObject,
) -> *mut ffi::PyObject;

/// The trampoline of slot `I` (a `METH_VARARGS | METH_KEYWORDS` C function).
unsafe extern "C" fn trampoline<const I: usize>(
    receiver: *mut ffi::PyObject,
    args: *mut ffi::PyObject,
    kwargs: *mut ffi::PyObject,
) -> *mut ffi::PyObject {
    // SAFETY: CPython calls it with the GIL held and the arguments of a METH_VARARGS |
    // METH_KEYWORDS function, as `call_slot` expects.
    unsafe { call_slot(&SLOTS[I], receiver, args, kwargs) }
}

macro_rules! row {
    ($r:literal) => {
        [
            trampoline::<{ $r * 16 }>,
            trampoline::<{ $r * 16 + 1 }>,
            trampoline::<{ $r * 16 + 2 }>,
            trampoline::<{ $r * 16 + 3 }>,
            trampoline::<{ $r * 16 + 4 }>,
            trampoline::<{ $r * 16 + 5 }>,
            trampoline::<{ $r * 16 + 6 }>,
            trampoline::<{ $r * 16 + 7 }>,
            trampoline::<{ $r * 16 + 8 }>,
            trampoline::<{ $r * 16 + 9 }>,
            trampoline::<{ $r * 16 + 10 }>,
            trampoline::<{ $r * 16 + 11 }>,
            trampoline::<{ $r * 16 + 12 }>,
            trampoline::<{ $r * 16 + 13 }>,
            trampoline::<{ $r * 16 + 14 }>,
            trampoline::<{ $r * 16 + 15 }>,
        ]
    };
}

/// One trampoline per slot, by slot number (row, column).
static TRAMPOLINES: [[Trampoline; 16]; POOL / 16] = [
    row!(0),
    row!(1),
    row!(2),
    row!(3),
    row!(4),
    row!(5),
    row!(6),
    row!(7),
    row!(8),
    row!(9),
    row!(10),
    row!(11),
    row!(12),
    row!(13),
    row!(14),
    row!(15),
];

/// Calls the slot's original function; a `TypeError` it raised becomes `InvalidArgumentError`.
///
/// # Safety
/// The GIL is held; `args` is a tuple, `kwargs` null or a dict; the slot is filled.
unsafe fn call_slot(
    slot: &Slot,
    receiver: *mut ffi::PyObject,
    args: *mut ffi::PyObject,
    kwargs: *mut ffi::PyObject,
) -> *mut ffi::PyObject {
    let original = slot.original.load(Ordering::Relaxed);
    // SAFETY: the caller holds the GIL and passes what CPython passes a METH_VARARGS |
    // METH_KEYWORDS function; the original has the signature its flags said.
    unsafe {
        let result = if slot.takes_none.load(Ordering::Relaxed) {
            let keywords = if kwargs.is_null() {
                0
            } else {
                ffi::PyDict_Size(kwargs)
            };
            let given = ffi::PyTuple_Size(args) + keywords;
            if given != 0 {
                let name = CStr::from_ptr(slot.name.load(Ordering::Relaxed)).to_string_lossy();
                let py = Python::assume_attached();
                invalid(format!("{name}() takes no arguments ({given} given)")).restore(py);
                return std::ptr::null_mut();
            }
            let function: ffi::PyCFunction = std::mem::transmute(original);
            function(receiver, std::ptr::null_mut())
        } else {
            let function: ffi::PyCFunctionWithKeywords = std::mem::transmute(original);
            function(receiver, args, kwargs)
        };
        if result.is_null() {
            retag(Python::assume_attached());
        }
        result
    }
}

/// Replaces the pending exception, when it is exactly a `TypeError` (pyo3's or CPython's
/// refusal of the arguments), with an `InvalidArgumentError` of the same message; a `WrongTypeError`
/// naming the argument when pyo3 refused an argument's type (a parameter of a plain type, such
/// as `bool` or `String`, given another).
fn retag(py: Python<'_>) {
    // SAFETY: the GIL is held; PyErr_Occurred returns a borrowed pointer or null.
    let pending = unsafe { ffi::PyErr_Occurred() };
    // SAFETY: PyExc_TypeError is a static of the interpreter.
    if pending.is_null() || pending != unsafe { ffi::PyExc_TypeError } {
        return;
    }
    if let Some(refused) = PyErr::take(py) {
        let message = refused.value(py).to_string();
        match converted_argument(py, &refused, &message) {
            Some(argument) => wrong_type(format!("{argument}{}", expected_found(&message))),
            None => invalid(message),
        }
        .restore(py);
    }
}

/// pyo3's refusal of a conversion ("'int' object is not an instance of 'str'", "'None' is not
/// an instance of 'bool'") said as the package says it ("expected a str, found an int"); any
/// other message as it is.
fn expected_found(message: &str) -> String {
    let Some((found, expected)) = message.split_once(" is not an instance of ") else {
        return message.to_string();
    };
    let unquoted = |text: &str| text.trim().trim_matches('\'').to_string();
    let found = unquoted(found.trim_end_matches(" object"));
    let found = if found == "None" {
        found
    } else {
        with_article(&found)
    };
    format!(
        "expected {}, found {found}",
        with_article(&unquoted(expected))
    )
}

/// When pyo3 refused an argument's conversion with `refused`, what names the argument ahead of
/// the message ("argument 'name': ", or "" when pyo3 did not note it); None for a refusal of the
/// arguments' number or names. pyo3 notes "while processing 'name'" on the refusal of a
/// conversion (Python 3.11 and later), and says "... is not an instance of ..." in any case.
fn converted_argument(py: Python<'_>, refused: &PyErr, message: &str) -> Option<String> {
    const NOTED: &str = "while processing ";
    let notes = refused.value(py).getattr("__notes__").ok();
    let noted = notes
        .and_then(|notes| notes.extract::<Vec<String>>().ok())
        .and_then(|notes| {
            notes
                .into_iter()
                .find_map(|n| n.strip_prefix(NOTED).map(str::to_string))
        });
    match noted {
        Some(argument) => Some(format!("argument {argument}: ")),
        None => message
            .contains(" is not an instance of ")
            .then(String::new),
    }
}

/// Points `def` at a trampoline of its own. Returns whether it took no arguments (its callers
/// must then call it as a METH_VARARGS | METH_KEYWORDS function).
///
/// # Safety
/// `def` is the live, writable `PyMethodDef` of a function of this module, not yet guarded.
unsafe fn guard_def(def: *mut ffi::PyMethodDef, name: &str) -> PyResult<bool> {
    let binding = ffi::METH_CLASS | ffi::METH_STATIC | ffi::METH_COEXIST;
    // SAFETY: the caller gives a live def.
    let flags = unsafe { (*def).ml_flags };
    let takes_none = match flags & !binding {
        f if f == ffi::METH_VARARGS | ffi::METH_KEYWORDS => false,
        f if f == ffi::METH_NOARGS => true,
        _ => {
            return Err(invalid(format!(
                "{name}: expected a compiled function taking (args, kwargs) or no arguments, \
                 found the calling convention {flags:#x}"
            )))
        }
    };
    let index = USED.fetch_add(1, Ordering::Relaxed);
    if index >= POOL {
        return Err(invalid(format!(
            "{name}: expected at most {POOL} compiled functions and methods (arity::POOL), found more"
        )));
    }
    let slot = &SLOTS[index];
    let text = CString::new(name).unwrap_or_default();
    slot.name.store(text.into_raw(), Ordering::Relaxed);
    slot.takes_none.store(takes_none, Ordering::Relaxed);
    // SAFETY: the def is live and writable (pyo3 leaks the defs it gives CPython); every union
    // member is a function pointer of one size.
    unsafe {
        slot.original
            .store((*def).ml_meth.PyCFunction as *mut c_void, Ordering::Relaxed);
        (*def).ml_meth = ffi::PyMethodDefPointer {
            PyCFunctionWithKeywords: TRAMPOLINES[index / 16][index % 16],
        };
        (*def).ml_flags = ffi::METH_VARARGS | ffi::METH_KEYWORDS | (flags & binding);
    }
    Ok(takes_none)
}

/// The name of `object`'s type (`method_descriptor`, `staticmethod`...).
fn kind(object: &Bound<'_, PyAny>) -> PyResult<String> {
    object.get_type().name()?.extract()
}

/// What one attribute of the module or of a class is, for the guard.
enum Entry<'py> {
    /// A method or class method (a method descriptor).
    Descriptor(Bound<'py, PyAny>),
    /// A module's function, or the function inside a static method.
    Function(Bound<'py, PyAny>),
}

/// Guards every compiled function of `module`, and the methods, static and class methods and
/// constructor of each of its `classes`.
pub fn guard_module(module: &Bound<'_, PyModule>, classes: &[Bound<'_, PyType>]) -> PyResult<()> {
    let mut entries = Vec::new();
    for (_, value) in module.dict().iter() {
        if kind(&value)? == "builtin_function_or_method" {
            entries.push(Entry::Function(value));
        }
    }
    for class in classes {
        let members = class.getattr("__dict__")?.call_method0("items")?;
        for item in members.try_iter()? {
            let (_, value): (Bound<'_, PyAny>, Bound<'_, PyAny>) = item?.extract()?;
            match kind(&value)?.as_str() {
                "method_descriptor" | "classmethod_descriptor" => {
                    entries.push(Entry::Descriptor(value))
                }
                "staticmethod" => entries.push(Entry::Function(value.getattr("__func__")?)),
                _ => {}
            }
        }
    }
    // How CPython calls a METH_VARARGS | METH_KEYWORDS method descriptor: taken from one, for the
    // descriptors of methods that took no arguments.
    let mut varargs_call: *mut c_void = std::ptr::null_mut();
    for entry in &entries {
        if let Entry::Descriptor(d) = entry {
            let descriptor = d.as_ptr() as *mut MethodDescriptor;
            // SAFETY: a method descriptor has this layout; its def is live.
            let flags = unsafe { (*(*descriptor).d_method).ml_flags };
            if flags & (ffi::METH_VARARGS | ffi::METH_KEYWORDS)
                == ffi::METH_VARARGS | ffi::METH_KEYWORDS
                && kind(d)? == "method_descriptor"
            {
                // SAFETY: as above.
                varargs_call = unsafe { (*descriptor).vectorcall };
                break;
            }
        }
    }
    let mut done = HashSet::new();
    for entry in &entries {
        let (object, def) = match entry {
            // SAFETY: the layouts of the two kinds of object (see the module's documentation).
            Entry::Descriptor(d) => (d, unsafe {
                (*(d.as_ptr() as *mut MethodDescriptor)).d_method
            }),
            Entry::Function(f) => (f, unsafe { (*(f.as_ptr() as *mut BuiltinFunction)).m_ml }),
        };
        if !done.insert(def as usize) {
            continue;
        }
        let name = object.getattr("__qualname__")?.extract::<String>()?;
        // SAFETY: the def is live and writable, and guarded once (`done`).
        let took_none = unsafe { guard_def(def, &name)? };
        if !took_none {
            continue;
        }
        match entry {
            Entry::Descriptor(d) if kind(d)? == "method_descriptor" => {
                if varargs_call.is_null() {
                    return Err(invalid(format!(
                        "{name}: expected a method taking arguments in the module, found none"
                    )));
                }
                // SAFETY: the descriptor's call now reads its def as the (args, kwargs) kind.
                unsafe { (*(d.as_ptr() as *mut MethodDescriptor)).vectorcall = varargs_call };
            }
            // A class method descriptor and a function are called by their def's flags.
            Entry::Descriptor(_) => {}
            Entry::Function(f) => {
                // SAFETY: without a vectorcall, CPython calls the function by its def's flags.
                unsafe {
                    (*(f.as_ptr() as *mut BuiltinFunction)).vectorcall = std::ptr::null_mut()
                };
            }
        }
    }
    for class in classes {
        guard_constructor(class)?;
    }
    Ok(())
}

/// Gives `class` a `__new__` that calls its compiled constructor (its `tp_new` slot) and turns a
/// `TypeError` refusing the arguments into `InvalidArgumentError`.
fn guard_constructor(class: &Bound<'_, PyType>) -> PyResult<()> {
    let py = class.py();
    // SAFETY: a live type; Py_tp_new is a slot every type may have.
    let slot = unsafe { ffi::PyType_GetSlot(class.as_type_ptr(), ffi::Py_tp_new) };
    if slot.is_null() {
        return Ok(());
    }
    // SAFETY: the tp_new slot holds a newfunc.
    let make: ffi::newfunc = unsafe { std::mem::transmute(slot) };
    let name = class.name()?.to_string();
    let signature = match class.getattr("__text_signature__") {
        Ok(text) if !text.is_none() => text.extract::<String>()?,
        _ => "()".to_string(),
    };
    let parameters = signature.trim_start_matches('(').trim_end_matches(')');
    let separator = if parameters.is_empty() { "" } else { ", " };
    let doc =
        CString::new(format!("__new__(cls{separator}{parameters})\n--\n\n")).unwrap_or_default();
    let doc: &'static CStr = Box::leak(doc.into_boxed_c_str());
    let own: Py<PyType> = class.clone().unbind();
    let new = PyCFunction::new_closure(
        py,
        Some(c"__new__"),
        Some(doc),
        move |args: &Bound<'_, PyTuple>,
              kwargs: Option<&Bound<'_, PyDict>>|
              -> PyResult<Py<PyAny>> {
            let py = args.py();
            let own = own.bind(py);
            let first = args.get_item(0).ok();
            if !first.as_ref().is_some_and(|c| c.is(own)) {
                return Err(invalid(format!(
                    "{name}.__new__: expected the class {name} as the first argument, found {}",
                    first.map_or("none".to_string(), |c| c
                        .repr()
                        .map_or("a value".to_string(), |r| r.to_string()))
                )));
            }
            let rest = args.get_slice(1, args.len());
            let kwargs = kwargs.map_or(std::ptr::null_mut(), |k| k.as_ptr());
            // SAFETY: the GIL is held; the class's own constructor with a tuple and a dict.
            let made = unsafe { make(own.as_type_ptr(), rest.as_ptr(), kwargs) };
            if made.is_null() {
                retag(py);
                return Err(PyErr::fetch(py));
            }
            // SAFETY: tp_new returns a new reference.
            Ok(unsafe { Bound::from_owned_ptr(py, made) }.unbind())
        },
    )?;
    let builtins = py.import("builtins")?;
    let as_static = builtins.getattr("staticmethod")?.call1((new,))?;
    class.setattr("__new__", as_static)
}
