//! The optional cut points of a float datapath built of [`FpAdd`](super::add::FpAdd) and
//! [`FpMul`](super::mul::FpMul) units (the float slab tester, the float bundle tester): one bit each of
//! the datapath's `CUTS` parameter, each the cut of the same name in every adder or every multiplier of
//! the datapath. A datapath's latency grows by one clock per cut set.

/// [`crate::fp::add::cut::ALIGN`] in every adder.
pub const ADD_ALIGN: usize = 1 << 0;
/// [`crate::fp::add::cut::NORM`] in every adder.
pub const ADD_NORM: usize = 1 << 1;
/// [`crate::fp::mul::cut::RAW`] in every multiplier.
pub const MUL_RAW: usize = 1 << 2;
/// [`crate::fp::mul::cut::PRODUCT`] in every multiplier.
pub const MUL_PRODUCT: usize = 1 << 3;
/// Every optional cut.
pub const ALL: usize = ADD_ALIGN | ADD_NORM | MUL_RAW | MUL_PRODUCT;

/// The adders' cuts of a configuration.
pub const fn add(cuts: usize) -> usize {
    (if cuts & ADD_ALIGN != 0 {
        crate::fp::add::cut::ALIGN
    } else {
        0
    }) | (if cuts & ADD_NORM != 0 {
        crate::fp::add::cut::NORM
    } else {
        0
    })
}

/// The multipliers' cuts of a configuration.
pub const fn mul(cuts: usize) -> usize {
    (if cuts & MUL_RAW != 0 {
        crate::fp::mul::cut::RAW
    } else {
        0
    }) | (if cuts & MUL_PRODUCT != 0 {
        crate::fp::mul::cut::PRODUCT
    } else {
        0
    })
}
