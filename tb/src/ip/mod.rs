//! The exported cores as IP: port-word files for any simulator ([`words`]), the encoder and decoder of
//! the pipelined testers' ports ([`slab_in_row`], [`slab_out_row`], [`slab_out_of_row`]), the
//! datasheets ([`datasheet`]) and the packaging ([`package`]: FuseSoC cores, GTKWave save files).
//! Which modules exist, with their family and latency, is `rtl::export::catalog`.

pub mod datasheet;
pub mod family_docs;
pub mod package;
pub mod words;

use crate::slab::ports::{in_word, TesterCtx};
use crate::verilator::Port;

/// The hardware tag of the `seq`-th test of a stream (counting from 0): its low 16 bits. The pipelined
/// testers return results in order, so a decoder matches result `n` with test `n` and checks the tag.
pub fn seq_tag(seq: usize) -> u16 {
    seq as u16
}

/// The input words of one test of a slab-shaped tester (slab or chained cull-plane, either datapath),
/// one per column of `cols` ([`words::columns`] of the inputs), with tag `tag`.
pub fn slab_in_row<C: TesterCtx>(
    ctx: &C,
    cols: &[Port],
    tag: u16,
    r: &C::Ray,
    b: &C::Box,
) -> Result<Vec<u64>, String> {
    let v = Some((*r, *b));
    cols.iter()
        .map(|p| in_word(ctx, &p.name, tag, &v))
        .collect()
}

/// The output words of a result `o` with tag `tag`, one per column of `cols` ([`words::columns`] of the
/// outputs: `tag_out`, `hit`, `t_entry`, `t_exit`).
pub fn slab_out_row<C: TesterCtx>(
    ctx: &C,
    cols: &[Port],
    tag: u16,
    o: &C::Out,
) -> Result<Vec<u64>, String> {
    let (hit, en, ex) = ctx.out_fields(o);
    cols.iter()
        .map(|p| match p.name.as_str() {
            "tag_out" => Ok(tag as u64),
            "hit" => Ok(hit as u64),
            "t_entry" => Ok(en),
            "t_exit" => Ok(ex),
            other => Err(format!("unknown output port {other}")),
        })
        .collect()
}

/// The tag and result of a row of output words (columns `cols`, as [`slab_out_row`] writes them).
pub fn slab_out_of_row<C: TesterCtx>(
    ctx: &C,
    cols: &[Port],
    row: &[u64],
) -> Result<(u16, C::Out), String> {
    let word = |name: &str| {
        cols.iter()
            .position(|p| p.name == name)
            .map(|k| row[k])
            .ok_or_else(|| format!("no output port {name}"))
    };
    Ok((
        word("tag_out")? as u16,
        ctx.out_from_fields(word("hit")? != 0, word("t_entry")?, word("t_exit")?),
    ))
}
