//! The slab testers' configurations as the testbenches see them: `FixFormat` and `FloatFormat` as
//! [`TesterCtx`] (name, port codec, model, world interval, verdict).

use crate::xsim::{BlockCtx, TesterCtx};
use golden::format::fixed::{FixBox, FixFormat, FixRay};
use golden::format::float::FloatFormat;
use golden::slab::fix::{slab_fix, SlabFixOut};
use golden::slab::float::{slab_float, FloatBox, FloatRay, SlabFloatOut};
use rtl::slab::ports::{SlabFixPorts, SlabFloatPorts};

/// One fixed slab test for the pipeline: `None` is a bubble.
pub type SlabVec = Option<(FixRay, FixBox)>;

impl BlockCtx for FixFormat {
    type Ray = FixRay;
    type Box = FixBox;
    type Out = SlabFixOut;
    type Ports = SlabFixPorts;
    fn name(&self) -> String {
        FixFormat::name(self)
    }
    fn ports(&self) -> SlabFixPorts {
        SlabFixPorts
    }
    fn model(&self, r: &FixRay, b: &FixBox) -> SlabFixOut {
        slab_fix(self, r, b)
    }
    fn counts_as_hit(&self, o: &SlabFixOut) -> bool {
        o.hit
    }
}

impl TesterCtx for FixFormat {
    fn world(&self, r: &FixRay, o: &SlabFixOut) -> (bool, f64, f64) {
        (
            o.hit,
            r.t_entry_f64(self, o.t_entry),
            r.t_exit_f64(self, o.t_exit),
        )
    }
    fn judge(
        &self,
        r: &FixRay,
        o: &SlabFixOut,
        exact: &golden::exact::ExactHit,
    ) -> golden::slab::check::Verdict {
        golden::slab::check::judge_fix(self, r, o, exact)
    }
}

impl BlockCtx for FloatFormat {
    type Ray = FloatRay;
    type Box = FloatBox;
    type Out = SlabFloatOut;
    type Ports = SlabFloatPorts;
    fn name(&self) -> String {
        FloatFormat::name(self)
    }
    fn ports(&self) -> SlabFloatPorts {
        SlabFloatPorts
    }
    fn model(&self, r: &FloatRay, b: &FloatBox) -> SlabFloatOut {
        slab_float(self, r, b)
    }
    fn counts_as_hit(&self, o: &SlabFloatOut) -> bool {
        o.hit
    }
}

impl TesterCtx for FloatFormat {
    fn world(&self, _: &FloatRay, o: &SlabFloatOut) -> (bool, f64, f64) {
        (o.hit, self.to_f64(o.t_entry), self.to_f64(o.t_exit))
    }
    fn judge(
        &self,
        _: &FloatRay,
        o: &SlabFloatOut,
        exact: &golden::exact::ExactHit,
    ) -> golden::slab::check::Verdict {
        golden::slab::float::judge_float(self, o, exact)
    }
}
