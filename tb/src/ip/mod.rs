//! The exported cores as IP: port-word files for any simulator ([`words`]; a test's and a result's words
//! come from the block's port codec, [`crate::xsim::in_row`], [`crate::xsim::out_row`],
//! [`crate::xsim::out_of_row`]), the
//! datasheets ([`datasheet`]) and the packaging ([`package`]: FuseSoC cores, GTKWave save files).
//! Which modules exist, with their family and latency, is `rtl::export::catalog`.

pub mod datasheet;
pub mod family_docs;
pub mod package;
pub mod words;

/// The hardware tag of the `seq`-th test of a stream (counting from 0): its low 16 bits. The pipelined
/// testers return results in order, so a decoder matches result `n` with test `n` and checks the tag.
pub fn seq_tag(seq: usize) -> u16 {
    seq as u16
}
