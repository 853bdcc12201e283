//! The files of an MJCF model: the main file and every file it
//! `<include>`s (recursively, paths relative to the main file's
//! directory, as MuJoCo resolves them), each parsed with `roxmltree`, and
//! the elements of a parent with its `<include>`s replaced by the children
//! of the included file's `<mujoco>`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use roxmltree::{Document, Node};

use super::{Loc, Problem};
use crate::urdf::xml::{offset_of, tag_range};

/// A file's path and text.
pub(super) struct Source {
    pub path: PathBuf,
    pub text: String,
}

/// An element and the file it is in (an index into the sources).
#[derive(Clone, Copy)]
pub(super) struct Element<'a> {
    pub file: usize,
    pub node: Node<'a, 'a>,
}

impl Element<'_> {
    /// The element's tag name.
    pub fn tag(&self) -> &str {
        self.node.tag_name().name()
    }

    /// Where the element's start tag is.
    pub fn loc(&self) -> Loc {
        Loc {
            file: self.file,
            range: tag_range(self.node),
        }
    }
}

/// Reads the main file at `path` (whose text is `text`) and every file it
/// includes, with the problems found: unreadable or malformed files, an
/// include without `file`, a file included twice.
pub(super) fn load(path: &Path, text: String) -> (Vec<Source>, Vec<Problem>) {
    let mut sources = vec![Source {
        path: path.to_owned(),
        text,
    }];
    let dir = path.parent().map(Path::to_owned).unwrap_or_default();
    let mut problems = Vec::new();
    let mut next = 0;
    while next < sources.len() {
        let document = match parse(&sources[next].text, next) {
            Ok(document) => document,
            Err(problem) => {
                problems.push(problem);
                next += 1;
                continue;
            }
        };
        let mut found = Vec::new();
        for node in document.descendants().filter(|n| n.has_tag_name("include")) {
            let at = Loc {
                file: next,
                range: tag_range(node),
            };
            let Some(file) = node.attribute("file") else {
                problems.push(Problem::new(
                    at,
                    "`<include>` needs the attribute `file`".to_owned(),
                ));
                continue;
            };
            found.push((dir.join(file), file.to_owned(), at));
        }
        for (included, written, at) in found {
            if sources.iter().any(|s| s.path == included) {
                problems.push(Problem::new(
                    at,
                    format!(
                        "`{written}` is included twice (or includes itself); MuJoCo includes a \
                         file once"
                    ),
                ));
                continue;
            }
            match std::fs::read_to_string(&included) {
                Ok(text) => sources.push(Source {
                    path: included,
                    text,
                }),
                Err(error) => problems.push(Problem::new(
                    at,
                    format!(
                        "cannot read the included file `{written}` ({}): {error}",
                        included.display()
                    ),
                )),
            }
        }
        next += 1;
    }
    (sources, problems)
}

/// Parses the text of file `file`, or the problem at the first fault.
pub(super) fn parse(text: &str, file: usize) -> Result<Document<'_>, Problem> {
    Document::parse(text).map_err(|e| {
        let pos = e.pos();
        let offset = offset_of(text, pos.row, pos.col);
        Problem::new(
            Loc {
                file,
                range: offset..offset + 1,
            },
            format!("malformed XML: {e}"),
        )
    })
}

/// The parsed files, and where each `<include>` leads.
pub(super) struct Files<'a> {
    documents: Vec<Document<'a>>,
    /// `(file, start of the <include> tag)` → the included file.
    includes: HashMap<(usize, usize), usize>,
}

impl<'a> Files<'a> {
    /// The files of `sources`, all parsed already once by [`load`].
    pub fn new(sources: &'a [Source]) -> Result<Self, Vec<Problem>> {
        let mut documents = Vec::new();
        for (i, source) in sources.iter().enumerate() {
            documents.push(parse(&source.text, i).map_err(|p| vec![p])?);
        }
        let dir = sources[0]
            .path
            .parent()
            .map(Path::to_owned)
            .unwrap_or_default();
        let mut includes = HashMap::new();
        for (i, document) in documents.iter().enumerate() {
            for node in document.descendants().filter(|n| n.has_tag_name("include")) {
                let target = node.attribute("file").map(|f| dir.join(f));
                if let Some(j) = sources
                    .iter()
                    .position(|s| Some(&s.path) == target.as_ref())
                {
                    includes.insert((i, node.range().start), j);
                }
            }
        }
        Ok(Files {
            documents,
            includes,
        })
    }

    /// The root element of the main file.
    pub fn root(&'a self) -> Element<'a> {
        Element {
            file: 0,
            node: self.documents[0].root_element(),
        }
    }

    /// The child elements of `parent`, with each `<include>` replaced by
    /// the children of the included file's root element.
    pub fn children(&'a self, parent: Element<'a>) -> Vec<Element<'a>> {
        let mut out = Vec::new();
        for node in parent.node.children().filter(Node::is_element) {
            let child = Element {
                file: parent.file,
                node,
            };
            match self.includes.get(&(parent.file, node.range().start)) {
                Some(&j) if node.has_tag_name("include") => {
                    let root = Element {
                        file: j,
                        node: self.documents[j].root_element(),
                    };
                    out.extend(self.children(root));
                }
                _ => out.push(child),
            }
        }
        out
    }
}
