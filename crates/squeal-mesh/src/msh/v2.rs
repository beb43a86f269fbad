//! MSH 2.2 `$Nodes` and `$Elements`, ASCII and binary.
//!
//! ASCII: `$Nodes` is a count, then lines `tag x y z`; `$Elements` a count, then lines
//! `tag type number-of-tags tags... nodes...`, whose first tag is the physical group (0 for
//! none) and second the elementary entity. Binary: the counts stay ASCII lines; nodes are
//! `int tag, double x, y, z`; elements come in blocks headed by `int type, count, number-of-tags`,
//! each element then `int tag, int tags[number-of-tags], int nodes[...]`.

use super::types::{self, ElementType};
use super::{Owner, Reader};
use crate::MeshError;
use crate::msh::cursor::Fields;

/// Bytes of one binary node: `int` tag and three doubles.
const BINARY_NODE_BYTES: u64 = 4 + 3 * 8;
/// The shortest ASCII node line, `1 0 0 0` and its newline.
const ASCII_NODE_BYTES: u64 = 8;
/// The shortest ASCII element line, `1 15 0 1` and its newline.
const ASCII_ELEMENT_BYTES: u64 = 9;

pub(super) fn read_nodes(r: &mut Reader<'_>) -> Result<(), MeshError> {
    let mut f = r.cur.expect_fields("the number of nodes")?;
    let count = f.u64("the number of nodes")?;
    f.end("the number of nodes")?;
    let min_bytes = if r.cur.binary {
        BINARY_NODE_BYTES
    } else {
        ASCII_NODE_BYTES
    };
    let count = r.cur.check_count(count, min_bytes, "nodes", f.location)?;
    for _ in 0..count {
        let (id, x, at) = if r.cur.binary {
            binary_node(r)?
        } else {
            ascii_node(r)?
        };
        r.builder.add_node(id, x).map_err(|m| r.cur.error(at, m))?;
    }
    r.cur.expect_end("Nodes")
}

fn ascii_node(r: &mut Reader<'_>) -> Result<(u64, [f64; 3], crate::Location), MeshError> {
    let mut f = r.cur.expect_fields("a node line (tag x y z)")?;
    let id = f.u64("a node tag")?;
    let x = [
        f.f64("the x coordinate")?,
        f.f64("the y coordinate")?,
        f.f64("the z coordinate")?,
    ];
    f.end("the node's coordinates")?;
    Ok((id, x, f.location))
}

fn binary_node(r: &mut Reader<'_>) -> Result<(u64, [f64; 3], crate::Location), MeshError> {
    let at = r.cur.here();
    let id = r.cur.uint("a node tag (int)")?;
    let x = [
        r.cur.double("the x coordinate")?,
        r.cur.double("the y coordinate")?,
        r.cur.double("the z coordinate")?,
    ];
    Ok((id, x, at))
}

pub(super) fn read_elements(r: &mut Reader<'_>) -> Result<(), MeshError> {
    let mut f = r.cur.expect_fields("the number of elements")?;
    let count = f.u64("the number of elements")?;
    f.end("the number of elements")?;
    if r.cur.binary {
        // Each element takes at least its tag and one node: 8 bytes.
        r.cur.check_count(count, 8, "elements", f.location)?;
        binary_elements(r, count)?;
    } else {
        let count = r
            .cur
            .check_count(count, ASCII_ELEMENT_BYTES, "elements", f.location)?;
        let mut nodes = Vec::new();
        for _ in 0..count {
            ascii_element(r, &mut nodes)?;
        }
    }
    r.cur.expect_end("Elements")
}

/// The type of an element type code, or an error.
fn lookup(
    code: i32,
    fail: impl FnOnce(String) -> MeshError,
) -> Result<&'static ElementType, MeshError> {
    types::element_type(code).ok_or_else(|| fail(format!("unknown element type {code}")))
}

/// The group an element's physical tag names (tag 0: none).
fn owner(kind: &ElementType, physical: i32) -> Option<Owner> {
    (physical != 0).then_some((kind.dim, physical))
}

fn ascii_element(r: &mut Reader<'_>, nodes: &mut Vec<u64>) -> Result<(), MeshError> {
    let mut f = r
        .cur
        .expect_fields("an element line (tag type number-of-tags tags... nodes...)")?;
    let id = f.u64("an element tag")?;
    let code = f.i32("an element type")?;
    let kind = lookup(code, |m| f.error(m))?;
    let num_tags = f.u64("the number of tags")?;
    let left = f.count_left() as u64;
    if left < num_tags || left - num_tags != kind.nodes as u64 {
        return Err(f.error(format!(
            "element {id} of type {code} ({}) has {} fields after its {num_tags} tags, expected {} node tags",
            kind.name,
            left.saturating_sub(num_tags),
            kind.nodes
        )));
    }
    let physical = tag(&mut f, num_tags, 0)?;
    // The elementary entity (second tag) and partition tags are checked as numbers, not used.
    for k in 1..num_tags {
        tag(&mut f, num_tags, k)?;
    }
    nodes.clear();
    for _ in 0..kind.nodes {
        nodes.push(f.u64("a node tag")?);
    }
    r.element(id, kind, owner(kind, physical), nodes, f.location)
}

/// Tag `k` of an element (0 if the element has fewer tags).
fn tag(f: &mut Fields<'_>, num_tags: u64, k: u64) -> Result<i32, MeshError> {
    if k < num_tags {
        f.i32(if k == 0 {
            "the physical tag"
        } else {
            "an element tag"
        })
    } else {
        Ok(0)
    }
}

fn binary_elements(r: &mut Reader<'_>, count: u64) -> Result<(), MeshError> {
    let mut done = 0u64;
    let mut nodes = Vec::new();
    while done < count {
        let at = r.cur.here();
        let code = r.cur.int("an element type (block header)")?;
        let kind = lookup(code, |m| r.cur.error(at, m))?;
        let in_block = r.cur.uint("the number of elements in the block")?;
        let num_tags = r.cur.uint("the number of tags")?;
        if in_block > count - done {
            return Err(r.cur.error(
                at,
                format!("element block of {in_block} elements, but only {} of the declared total are left", count - done),
            ));
        }
        let per_element = (1 + kind.nodes as u64)
            .saturating_add(num_tags)
            .saturating_mul(4);
        r.cur
            .check_count(in_block, per_element, "elements in the block", at)?;
        for _ in 0..in_block {
            let at = r.cur.here();
            let id = r.cur.uint("an element tag")?;
            let physical = if num_tags > 0 {
                r.cur.int("the physical tag")?
            } else {
                0
            };
            r.cur.skip(num_tags.saturating_sub(1) * 4, "element tags")?;
            nodes.clear();
            for _ in 0..kind.nodes {
                nodes.push(r.cur.uint("a node tag")?);
            }
            r.element(id, kind, owner(kind, physical), &nodes, at)?;
        }
        done += in_block;
    }
    Ok(())
}
