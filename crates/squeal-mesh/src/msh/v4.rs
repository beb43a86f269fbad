//! MSH 4.1 `$Entities`, `$Nodes` and `$Elements`, ASCII and binary.
//!
//! Binary files hold the same fields as ASCII ones, as `int` (4 bytes), `size_t` (8 bytes) and
//! `double` (8 bytes) in the byte order of the file; ASCII files write one record per line
//! (an entity, a node tag, a node's coordinates, an element), which is what this reader
//! expects.

use super::Reader;
use super::types::{self, ElementType};
use crate::{Location, MeshError};

/// `$Entities`: points `tag x y z physicals`, then curves, surfaces and volumes
/// `tag bounding-box physicals bounding-entities`; only the physical tags are kept.
pub(super) fn read_entities(r: &mut Reader<'_>) -> Result<(), MeshError> {
    let (counts, at) = if r.cur.binary {
        let at = r.cur.here();
        let mut counts = [0u64; 4];
        for c in &mut counts {
            *c = r.cur.size("the number of entities (size_t)")?;
        }
        (counts, at)
    } else {
        let mut f = r
            .cur
            .expect_fields("the numbers of points, curves, surfaces and volumes")?;
        let mut counts = [0u64; 4];
        for c in &mut counts {
            *c = f.u64("a number of entities")?;
        }
        f.end("the numbers of entities")?;
        (counts, f.location)
    };
    for (dim, &count) in (0i32..).zip(&counts) {
        // Shortest records: binary point 4+24+8 bytes, other binary entities 4+48+16 bytes;
        // ASCII fields take at least 2 bytes each (5 for a point, 9 otherwise).
        let min_bytes = match (r.cur.binary, dim) {
            (true, 0) => 36,
            (true, _) => 68,
            (false, 0) => 10,
            (false, _) => 18,
        };
        let count = r.cur.check_count(count, min_bytes, "entities", at)?;
        for _ in 0..count {
            let (tag, physicals) = if r.cur.binary {
                binary_entity(r, dim)?
            } else {
                ascii_entity(r, dim)?
            };
            r.entity_groups.insert((dim, tag), physicals);
        }
    }
    r.cur.expect_end("Entities")
}

fn ascii_entity(r: &mut Reader<'_>, dim: i32) -> Result<(i32, Vec<i32>), MeshError> {
    let mut f = r.cur.expect_fields("an entity line")?;
    let tag = f.i32("an entity tag")?;
    let coordinates = if dim == 0 { 3 } else { 6 };
    for _ in 0..coordinates {
        f.f64(if dim == 0 {
            "a point coordinate"
        } else {
            "a bounding-box coordinate"
        })?;
    }
    let n = f.u64("the number of physical tags")?;
    let mut physicals = Vec::new();
    for _ in 0..bounded(n, f.count_left()) {
        physicals.push(f.i32("a physical tag")?);
    }
    if dim > 0 {
        let n = f.u64("the number of bounding entities")?;
        for _ in 0..bounded(n, f.count_left()) {
            f.i32("a bounding entity tag")?;
        }
    }
    f.end("the entity")?;
    Ok((tag, physicals))
}

/// `n`, or one more than the fields left if `n` is larger: reading then stops with a
/// "found end of line" error instead of looping over a huge count.
fn bounded(n: u64, left: usize) -> u64 {
    n.min(left as u64 + 1)
}

fn binary_entity(r: &mut Reader<'_>, dim: i32) -> Result<(i32, Vec<i32>), MeshError> {
    let tag = r.cur.int("an entity tag")?;
    let coordinates = if dim == 0 { 3 } else { 6 };
    for _ in 0..coordinates {
        r.cur.double(if dim == 0 {
            "a point coordinate"
        } else {
            "a bounding-box coordinate"
        })?;
    }
    let at = r.cur.here();
    let n = r.cur.size("the number of physical tags (size_t)")?;
    let n = r.cur.check_count(n, 4, "physical tags", at)?;
    let mut physicals = Vec::with_capacity(n);
    for _ in 0..n {
        physicals.push(r.cur.int("a physical tag")?);
    }
    if dim > 0 {
        let at = r.cur.here();
        let n = r.cur.size("the number of bounding entities (size_t)")?;
        let n = r.cur.check_count(n, 4, "bounding entities", at)?;
        r.cur.skip(4 * n as u64, "bounding entity tags")?;
    }
    Ok((tag, physicals))
}

/// The header of `$Nodes` or `$Elements`: `numEntityBlocks numItems minTag maxTag`.
struct Header {
    blocks: u64,
    items: u64,
    at: Location,
}

fn read_header(r: &mut Reader<'_>, items: &str) -> Result<Header, MeshError> {
    let what =
        format!("the header (number of blocks, number of {items}, smallest and largest tag)");
    if r.cur.binary {
        let at = r.cur.here();
        let blocks = r.cur.size(&what)?;
        let items = r.cur.size(&what)?;
        r.cur.size(&what)?;
        r.cur.size(&what)?;
        Ok(Header { blocks, items, at })
    } else {
        let mut f = r.cur.expect_fields(&what)?;
        let blocks = f.u64("the number of blocks")?;
        let items = f.u64(&format!("the number of {items}"))?;
        f.u64("the smallest tag")?;
        f.u64("the largest tag")?;
        f.end(&what)?;
        Ok(Header {
            blocks,
            items,
            at: f.location,
        })
    }
}

/// The header of one entity block: `entityDim entityTag (parametric | elementType) count`.
struct Block {
    dim: i32,
    tag: i32,
    kind: i32,
    count: u64,
    at: Location,
}

fn read_block(r: &mut Reader<'_>, third: &str) -> Result<Block, MeshError> {
    let what = format!("a block header (entity dimension, entity tag, {third}, count)");
    let block = if r.cur.binary {
        let at = r.cur.here();
        let dim = r.cur.int(&what)?;
        let tag = r.cur.int(&what)?;
        let kind = r.cur.int(&what)?;
        let count = r.cur.size(&what)?;
        Block {
            dim,
            tag,
            kind,
            count,
            at,
        }
    } else {
        let mut f = r.cur.expect_fields(&what)?;
        let dim = f.i32("the entity dimension")?;
        let tag = f.i32("the entity tag")?;
        let kind = f.i32(third)?;
        let count = f.u64("the number of items in the block")?;
        f.end(&what)?;
        Block {
            dim,
            tag,
            kind,
            count,
            at: f.location,
        }
    };
    if !(0..=3).contains(&block.dim) {
        return Err(r.cur.error(
            block.at,
            format!("expected an entity dimension 0 to 3, found {}", block.dim),
        ));
    }
    Ok(block)
}

/// Checks that the blocks held as many items as the header declared.
fn check_total(r: &Reader<'_>, header: &Header, total: u64, items: &str) -> Result<(), MeshError> {
    if total == header.items {
        Ok(())
    } else {
        Err(r.cur.error(
            header.at,
            format!(
                "the header declares {} {items}, but the blocks hold {total}",
                header.items
            ),
        ))
    }
}

/// `$Nodes`: per entity block, the node tags, then their coordinates `x y z` (followed by
/// 1 to 3 parametric coordinates if the block is parametric; these are dropped).
pub(super) fn read_nodes(r: &mut Reader<'_>) -> Result<(), MeshError> {
    let header = read_header(r, "nodes")?;
    let (min_block, min_node) = if r.cur.binary { (20, 32) } else { (8, 8) };
    let blocks = r
        .cur
        .check_count(header.blocks, min_block, "node blocks", header.at)?;
    r.cur
        .check_count(header.items, min_node, "nodes", header.at)?;
    let mut total = 0u64;
    let mut tags = Vec::new();
    for _ in 0..blocks {
        let block = read_block(r, "parametric flag")?;
        let extra = match block.kind {
            0 => 0,
            1 => block.dim as usize,
            p => {
                return Err(r.cur.error(
                    block.at,
                    format!("expected the parametric flag 0 or 1, found {p}"),
                ));
            }
        };
        let min_bytes = if r.cur.binary {
            8 * (4 + extra as u64)
        } else {
            8
        };
        let count = r
            .cur
            .check_count(block.count, min_bytes, "nodes in the block", block.at)?;
        tags.clear();
        tags.reserve(count);
        for _ in 0..count {
            tags.push(node_tag(r)?);
        }
        for &id in &tags {
            let (x, at) = coordinates(r, extra)?;
            r.builder.add_node(id, x).map_err(|m| r.cur.error(at, m))?;
        }
        total = total.saturating_add(block.count);
    }
    check_total(r, &header, total, "nodes")?;
    r.cur.expect_end("Nodes")
}

fn node_tag(r: &mut Reader<'_>) -> Result<u64, MeshError> {
    if r.cur.binary {
        r.cur.size("a node tag (size_t)")
    } else {
        let mut f = r.cur.expect_fields("a node tag")?;
        let id = f.u64("a node tag")?;
        f.end("the node tag")?;
        Ok(id)
    }
}

/// One node's coordinates, and `extra` parametric coordinates that are dropped.
fn coordinates(r: &mut Reader<'_>, extra: usize) -> Result<([f64; 3], Location), MeshError> {
    const WHAT: [&str; 3] = ["the x coordinate", "the y coordinate", "the z coordinate"];
    let mut x = [0.0; 3];
    if r.cur.binary {
        let at = r.cur.here();
        for (xi, what) in x.iter_mut().zip(WHAT) {
            *xi = r.cur.double(what)?;
        }
        for _ in 0..extra {
            r.cur.double("a parametric coordinate")?;
        }
        Ok((x, at))
    } else {
        let mut f = r.cur.expect_fields("a node's coordinates")?;
        for (xi, what) in x.iter_mut().zip(WHAT) {
            *xi = f.f64(what)?;
        }
        for _ in 0..extra {
            f.f64("a parametric coordinate")?;
        }
        f.end("the node's coordinates")?;
        Ok((x, f.location))
    }
}

/// `$Elements`: per entity block (one element type), lines `tag node-tags...`.
pub(super) fn read_elements(r: &mut Reader<'_>) -> Result<(), MeshError> {
    let header = read_header(r, "elements")?;
    // Shortest block: binary 3 ints and a size_t; ASCII `0 1 15 0`. Shortest element: a tag and
    // one node, 16 bytes binary, 4 bytes ASCII.
    let (min_block, min_element) = if r.cur.binary { (20, 16) } else { (8, 4) };
    let blocks = r
        .cur
        .check_count(header.blocks, min_block, "element blocks", header.at)?;
    r.cur
        .check_count(header.items, min_element, "elements", header.at)?;
    let mut total = 0u64;
    let mut nodes = Vec::new();
    for _ in 0..blocks {
        let block = read_block(r, "element type")?;
        let kind = types::element_type(block.kind).ok_or_else(|| {
            r.cur
                .error(block.at, format!("unknown element type {}", block.kind))
        })?;
        if kind.dim != block.dim {
            return Err(r.cur.error(
                block.at,
                format!(
                    "element type {} ({}) has dimension {}, but the block's entity has dimension {}",
                    kind.code, kind.name, kind.dim, block.dim
                ),
            ));
        }
        let min_bytes = if r.cur.binary {
            8 * (1 + kind.nodes as u64)
        } else {
            2 * (1 + kind.nodes as u64)
        };
        let count = r
            .cur
            .check_count(block.count, min_bytes, "elements in the block", block.at)?;
        let owner = Some((block.dim, block.tag));
        for _ in 0..count {
            let (id, at) = if r.cur.binary {
                binary_element(r, kind, &mut nodes)?
            } else {
                ascii_element(r, kind, &mut nodes)?
            };
            r.element(id, kind, owner, &nodes, at)?;
        }
        total = total.saturating_add(block.count);
    }
    check_total(r, &header, total, "elements")?;
    r.cur.expect_end("Elements")
}

fn ascii_element(
    r: &mut Reader<'_>,
    kind: &ElementType,
    nodes: &mut Vec<u64>,
) -> Result<(u64, Location), MeshError> {
    let mut f = r.cur.expect_fields("an element line (tag node-tags...)")?;
    let id = f.u64("an element tag")?;
    let left = f.count_left();
    if left != kind.nodes {
        return Err(f.error(format!(
            "element {id} of type {} ({}) has {left} node tags, expected {}",
            kind.code, kind.name, kind.nodes
        )));
    }
    nodes.clear();
    for _ in 0..kind.nodes {
        nodes.push(f.u64("a node tag")?);
    }
    Ok((id, f.location))
}

fn binary_element(
    r: &mut Reader<'_>,
    kind: &ElementType,
    nodes: &mut Vec<u64>,
) -> Result<(u64, Location), MeshError> {
    let at = r.cur.here();
    let id = r.cur.size("an element tag (size_t)")?;
    nodes.clear();
    for _ in 0..kind.nodes {
        nodes.push(r.cur.size("a node tag (size_t)")?);
    }
    Ok((id, at))
}
