// The friction coefficient the stairs are taken to have, in one place: the judges that need one
// (the validator's dynamic check, the MuJoCo world and its stance forces) must see the same ground.
#pragma once

namespace stairplan {

/// Coulomb friction coefficient between a foot and the stairs, the default of every setting that
/// needs one (ContactWrenchSettings::friction, MjcfSettings::friction,
/// StanceForceSettings::friction). 0.8 stands for a dry tread under a rubber foot; it is not
/// measured. It has one owner so that the validator and MuJoCo judge a plan on the same ground and
/// their verdicts can be compared; a run on other ground sets each (validator.friction,
/// world.friction) for that run.
inline constexpr double kStairFriction = 0.8;

}  // namespace stairplan
