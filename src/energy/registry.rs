//! The list of energy-term kinds, written once. A network stores its terms by kind (one `Vec`
//! per kind, so that assembly is monomorphized); everything that walks all terms (Hessian
//! pattern, assembly, energies by category and by rod, reference updates, unknown positions)
//! goes through [`Terms::visit`]. Adding a term is its file plus one line in `term_kinds!`.

use super::{
    bend_twist::BendTwist, frame_bend_twist::FrameBendTwist, joint_rotation::JointRotation,
    joint_translation::JointTranslation, point_load::PointLoad,
    rotational_spring::RotationalSpring, spring::Spring, stretch::Stretch, torque::Torque, Term,
};

/// Something done to every kind of term in turn; `kind` is the kind's index in [`Terms::NAMES`].
pub trait TermVisitor {
    fn visit<const N: usize, E: Term<N>>(&mut self, kind: usize, terms: &[E]);
}

macro_rules! term_kinds {
    ($($field:ident: $ty:ty = $n:literal),* $(,)?) => {
        /// All energy terms of a network, grouped by kind.
        #[derive(Debug, Clone, Default)]
        pub struct Terms {
            $(pub $field: Vec<$ty>,)*
        }

        impl Terms {
            /// Kind names, in visiting order.
            pub const NAMES: &'static [&'static str] = &[$(stringify!($field)),*];

            /// Calls `v` on every kind, always in the order of [`Terms::NAMES`] (sums over terms
            /// are then reproducible).
            pub fn visit<V: TermVisitor>(&self, v: &mut V) {
                let mut kind = 0;
                $(
                    v.visit::<$n, $ty>(kind, &self.$field);
                    kind += 1;
                )*
                debug_assert_eq!(kind, Self::NAMES.len());
            }
        }
    };
}

term_kinds! {
    stretch: Stretch = 6,
    bend_twist: BendTwist = 11,
    frame_bend_twist: FrameBendTwist = 11,
    joint_rotation: JointRotation = 6,
    joint_translation: JointTranslation = 6,
    springs: Spring = 3,
    rotational_springs: RotationalSpring = 3,
    roller_normals: Spring = 3,
    loads: PointLoad = 3,
    torques: Torque = 3,
}

impl Terms {
    /// Number of kinds.
    pub const KINDS: usize = Self::NAMES.len();
}
