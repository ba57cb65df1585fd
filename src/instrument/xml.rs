//! A small element tree over quick-xml's event reader, for the XML inside .x3p and .xlsx
//! archives: element local names (namespace prefixes dropped), attributes and text, with the
//! predefined and character entities resolved. Nesting deeper than [`MAX_DEPTH`] is refused,
//! so a hostile document cannot exhaust the stack.

use std::path::Path;

use quick_xml::events::Event;
use quick_xml::{Reader, XmlVersion};

use super::bad;
use crate::Error;

/// Deepest element nesting accepted (the documents read here nest 5 levels).
const MAX_DEPTH: usize = 64;

/// One element: local name, attributes, child elements and its own text (concatenated).
#[derive(Debug, Default)]
pub(crate) struct Element {
    pub(crate) name: String,
    attrs: Vec<(String, String)>,
    pub(crate) children: Vec<Element>,
    pub(crate) text: String,
}

impl Element {
    /// The first child named `name`.
    pub(crate) fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }

    /// The element reached by following child names.
    pub(crate) fn at(&self, names: &[&str]) -> Option<&Element> {
        names.iter().try_fold(self, |e, n| e.child(n))
    }

    /// The trimmed text of the element reached by following child names.
    pub(crate) fn text_at(&self, names: &[&str]) -> Option<&str> {
        self.at(names).map(|e| e.text.trim())
    }

    /// The value of attribute `name` (local name).
    pub(crate) fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }
}

fn local(name: &[u8]) -> String {
    let name = String::from_utf8_lossy(name);
    match name.rsplit_once(':') {
        Some((_, l)) => l.to_string(),
        None => name.into_owned(),
    }
}

/// Parses `bytes`, the archive member `member` of the file `path`, into its root element.
pub(crate) fn parse(path: &Path, member: &str, bytes: &[u8]) -> Result<Element, Error> {
    let mut reader = Reader::from_reader(bytes);
    let err = |reader: &Reader<&[u8]>, msg: String| {
        bad(
            path,
            format!("{member}, byte {}: {msg}", reader.buffer_position()),
        )
    };
    // Open elements; the bottom one collects the root.
    let mut stack = vec![Element::default()];
    let mut buf = Vec::new();
    loop {
        let event = reader
            .read_event_into(&mut buf)
            .map_err(|e| err(&reader, format!("malformed XML: {e}")))?;
        match event {
            Event::Start(ref s) | Event::Empty(ref s) => {
                if stack.len() > MAX_DEPTH {
                    return Err(err(
                        &reader,
                        format!("elements nested deeper than {MAX_DEPTH}"),
                    ));
                }
                let mut el = Element {
                    name: local(s.name().as_ref()),
                    ..Element::default()
                };
                for a in s.attributes().flatten() {
                    let v = a
                        .normalized_value(XmlVersion::Implicit1_0)
                        .map_err(|e| err(&reader, format!("bad attribute: {e}")))?;
                    el.attrs.push((local(a.key.as_ref()), v.into_owned()));
                }
                if matches!(event, Event::Empty(_)) {
                    stack.last_mut().expect("stack").children.push(el);
                } else {
                    stack.push(el);
                }
            }
            Event::End(_) => {
                let el = stack.pop().expect("stack");
                let parent = stack
                    .last_mut()
                    .ok_or_else(|| err(&reader, "unbalanced end tag".into()))?;
                parent.children.push(el);
            }
            Event::Text(t) => {
                let t = t
                    .decode()
                    .map_err(|e| err(&reader, format!("text is not UTF-8: {e}")))?;
                stack.last_mut().expect("stack").text.push_str(&t);
            }
            Event::CData(t) => {
                stack
                    .last_mut()
                    .expect("stack")
                    .text
                    .push_str(&String::from_utf8_lossy(&t));
            }
            Event::GeneralRef(r) => {
                let name = r
                    .decode()
                    .map_err(|e| err(&reader, format!("entity is not UTF-8: {e}")))?;
                let text = match r.resolve_char_ref() {
                    Ok(Some(c)) => c.to_string(),
                    _ => quick_xml::escape::resolve_predefined_entity(&name)
                        .ok_or_else(|| err(&reader, format!("unknown entity &{name};")))?
                        .to_string(),
                };
                stack.last_mut().expect("stack").text.push_str(&text);
            }
            Event::Eof => break,
            _ => {}
        }
        buf.clear();
    }
    if stack.len() != 1 {
        return Err(err(
            &reader,
            format!(
                "the document ends inside <{}>",
                stack.last().expect("stack").name
            ),
        ));
    }
    stack
        .pop()
        .and_then(|doc| doc.children.into_iter().next())
        .ok_or_else(|| bad(path, format!("{member}: no root element")))
}
