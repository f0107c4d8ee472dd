#pragma once
/// Internal to src/physics (Bullet types inside): the Bullet engine behind a Physics
/// (Physics::Impl) and what it is made of, shared by the folder's sources, one concern a file:
///   physics.cpp           the public Physics: construction, init_state, one step, stats;
///   physics_build.cpp     building the groups' worlds, statics, floor patches, rubble and robots from World;
///   physics_joints.cpp    a robot's multibody and joints: made with its held joints fixed, motors and
///                         limits, self-locking gears holding and letting go, targets, read-back;
///   physics_groups.cpp    spreading bodies over groups (independent Bullet worlds) and stepping them
///                         on the worker threads;
///   physics_contacts.cpp  contacts: floor patches' materials, track belts, what touches each robot,
///                         and the trouble checks (non-finite poses, bodies flung away);
///   physics_restore.cpp   restoring a State and putting Bullet's hidden state into canonical form.
/// Nothing outside src/physics includes it (physics_internal.h is the bench's narrower handle).

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "physics/bullet_convert.h"
#include "physics/physics.h"
#include "world/robot_lumping.h"

namespace rescuesim {

namespace physics_detail {

/// What a Bullet collision object stands for, stored in its user index: a tag (bits 28-30), a
/// sub-index (bits 16-27: the robot of a robot's collider) and an index (bits 0-15: the static
/// object, the rubble body, or the robot's body).
enum Tag : int { kStatic = 0, kDynamic = 1, kRobot = 2 };
inline int encode(Tag tag, int index, int sub = 0) {
  RS_DEMAND(index >= 0 && index <= 0xffff && sub >= 0 && sub <= 0xfff,
            "physics encode: a collision object's index must fit 16 bits and its sub-index 12 bits");
  return (tag << 28) | (sub << 16) | index;
}
inline Tag tag_of(int code) { return static_cast<Tag>(code >> 28); }
inline int index_of(int code) { return code & 0xffff; }
inline int sub_of(int code) { return (code >> 16) & 0xfff; }

/// How far apart two shapes may be for Bullet to keep a (speculative) contact between them (m).
constexpr double kContactDistance = 0.03;
/// How far apart (m, each side) two bodies' bounding boxes must stay for them to step in
/// different groups: 10 cm beyond the contact distance, besides four steps of their speed.
constexpr double kGroupMargin = kContactDistance + 0.1;

/// Floor patches of other materials (World::ground), as the floor's body sees them. A patch is
/// not a solid of its own: a thin slab on the floor would give every wheel an edge to catch on
/// and a second contact (two frictions under one wheel), and a slab sunk flush with the floor
/// would still leave its rim for Bullet's contact generation to find. Instead the floor stays
/// one plane, and each contact with it takes its friction from the material under the contact
/// point: Bullet's contact-added callback, which Bullet calls for every contact point it makes or
/// refreshes with a body flagged CF_CUSTOM_MATERIAL_CALLBACK (only the floor is, and only in a
/// world with patches, so other worlds step exactly as before). The friction is combined as
/// Bullet combines it elsewhere, the product of the two bodies' (clamped to 10); likewise the
/// restitution.
struct GroundPatches {
  struct Patch {
    Polygon2 outline;
    Box2 box;
    double friction, restitution;
  };
  std::vector<Patch> patches;
  int floor_child = -1;  ///< with compound statics, the floor's child index in the compound (else -1)

  /// The patch under a point of the floor, or nullptr for the floor's own material.
  const Patch* at(const Vec2& p) const;
};

/// gContactAddedCallback: a floor contact's friction and restitution from the patch under it.
/// A pure function of the contact and the world, so it is safe on the worker threads.
bool ground_contact(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int, int index0, const btCollisionObjectWrapper* w1, int,
                    int index1);

/// A track belt over one collision shape of a robot body (LinkShape::belt_joint).
struct Belt {
  int child;        // the shape's index in its body's compound
  btVector3 axis;   // the belt's axis (the shape's z axis) in the collider's frame
  int sprocket;     // the Bullet link whose joint velocity drives it
  btScalar radius;  // m
};

/// Bullet's multibody solver, with moving contact surfaces: tracks. Bullet's rigid-body solver
/// takes a target sliding velocity per contact (btManifoldPoint::m_contactMotion1, the
/// conveyor-belt hook that Gazebo's tracked vehicles use through ODE's surface motion), but
/// its multibody solver (3.24 and upstream) ignores it and overwrites the friction
/// directions. So after Bullet has made its friction rows, each row at a contact with a belt
/// gets the belt's velocity as its target: the row's right-hand side is (target − relative
/// velocity) × its effective mass, and the target makes the two surfaces grip where the belt's
/// material and the ground move alike (v_A + u_A = v_B + u_B). The friction limit (μ × the
/// normal impulse) is untouched, so a belt slips where a real one would.
class BeltSolver final : public btMultiBodyConstraintSolver {
 public:
  bool belts = false;  ///< some collider carries a belt (else nothing is done per row)

  void convertContacts(btPersistentManifold** manifolds, int n, const btContactSolverInfo& info) override;
};

/// One robot as a Featherstone multibody: one Bullet link per rigid body of the robot (links
/// joined by fixed joints are lumped into one body, see world/robot_lumping.h).
struct RobotBody {
  /// How one moving joint makes its child body a Bullet link (the arguments of setupRevolute and
  /// its kin), kept to rebuild the multibody when a self-locking joint is held or let go.
  struct LinkSetup {
    JointSpec::Type type;
    btScalar mass;
    btVector3 inertia;
    int parent;
    btQuaternion rot_parent_to_this;  // at q = 0
    btVector3 axis, parent_com_to_pivot, pivot_to_com;
  };
  btMultiBody* mb = nullptr;
  std::unique_ptr<btMultiBody> owned_mb;
  std::vector<LinkSetup> setup;  // per Bullet link
  std::vector<char> held;        // per original joint: held rigid by its self-locking gear
  std::vector<double> held_q;    // per original joint: the position it is held at
  std::vector<std::unique_ptr<btMultiBodyConstraint>> owned_constraints;
  LumpedRobot lumped;                                     // bodies and moving joints, and where each link sits; a moving
                                                          // joint's Bullet link is its lumped index (lumped.lumped_joint)
  std::vector<int> bt_link;                               // per body: Bullet link index, -1 for the base
  std::vector<btMultiBodyLinkCollider*> colliders;        // per body
  std::vector<btMultiBodyJointMotor*> motors;             // per original joint, nullptr when uncontrolled
  std::vector<Pose3> X_BF;                                // per body: Bullet's frame (centre of mass, principal axes) in the body frame
  std::vector<char> top;                                  // per original link: it is its body's own frame
  std::vector<btMultiBodyConstraint*> constraints;        // motors and limits, in build order
  std::vector<std::unique_ptr<std::vector<Belt>>> belts;  // per body with belts: its colliders' user pointer
};

/// One Bullet world of its own: a share of the robots and rubble, and its own static body for
/// every static object (the shapes are shared, and only read while stepping). Groups share no
/// mutable Bullet object, so they step at the same time on different threads. Debian's Bullet
/// is built without BT_THREADSAFE, which rules out stepping the islands of one world in parallel;
/// worlds of their own need nothing of Bullet but that two instances be independent. What is
/// left shared are Bullet's statistics counters (plain ints such as gNumManifold), whose value
/// nothing reads. Its profiler is compiled out (no BT_ENABLE_PROFILE).
struct PhysicsGroup {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  BeltSolver solver;
  btMultiBodyDynamicsWorld dynamics{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btRigidBody>> statics;  // one per static object (or one compound), build order

  explicit PhysicsGroup(const btDefaultCollisionConstructionInfo& info) : config(info) {}
};

}  // namespace physics_detail

/// The Bullet engine of a Physics: its groups' worlds and every body in them, built once from
/// the World (which outlives it). Its functions are defined in the files listed above.
struct Physics::Impl {
  using GroundPatches = physics_detail::GroundPatches;
  using RobotBody = physics_detail::RobotBody;
  using PhysicsGroup = physics_detail::PhysicsGroup;
  using Belt = physics_detail::Belt;

  const World& world;
  PhysicsOptions options;
  bullet::ShapeStore shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  /// The static objects' shapes, poses, materials and user codes, built once for every group.
  struct StaticPart {
    btCollisionShape* shape;
    Pose3 X;
    int material;
    int code;
  };
  std::vector<StaticPart> static_parts;
  std::unique_ptr<GroundPatches> ground;             // World::ground for the floor's contact callback; null without patches
  std::vector<std::unique_ptr<btRigidBody>> rubble;  // per World::dynamics
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  std::vector<RobotBody> robots;
  std::vector<std::unique_ptr<PhysicsGroup>> groups;
  std::vector<int> robot_group;   // per robot: the group whose world holds it (-1: none yet)
  std::vector<int> rubble_group;  // per rubble body
  /// Names of the things a robot should not hit: walls, obstacles, victims, other robots.
  std::set<std::string> obstacle_names = obstacle_names_of(world);

  // physics_build.cpp
  Impl(const World& w, const PhysicsOptions& o);
  ~Impl();
  const MaterialSpec& material(int i) const { return world.materials[static_cast<std::size_t>(i)]; }
  static std::unique_ptr<btRigidBody> make_body(btCollisionShape* shape, btMotionState* motion, const Pose3& X, double mass,
                                                const Vec3& inertia, const MaterialSpec& m, int code);
  void build_statics();
  /// The floor patches (World::ground) with their materials; nothing when the world has none.
  void build_ground();
  /// A group's own static bodies, in build order; the floor's (static part 0, World::statics[0])
  /// asks for the floor patches' callback when there are patches.
  void add_statics(PhysicsGroup& g) const;
  void build_rubble();
  /// True when a body's lowest point lies on the floor or on a platform top (within 1 mm).
  bool resting_on_ground(const btRigidBody& b) const;
  void build_robot(int r);
  /// The belts over body `l`'s colliding shapes, numbered as its compound's children.
  static std::unique_ptr<std::vector<Belt>> belts_of(const RobotBody& body, std::size_t l);

  // physics_joints.cpp
  /// A multibody of the robot's Bullet links, each held joint (RobotBody::held) a fixed link at
  /// its held position; at rest at the origin.
  static std::unique_ptr<btMultiBody> make_multibody(const RobotBody& body);
  /// Points the robot's colliders at its (new) multibody.
  static void attach_colliders(RobotBody& body);
  /// The robot's actuators, per joint of the description: velocity motors (position loops run on
  /// top of them), Coulomb friction on passive joints (a motor holding zero speed with a bounded
  /// force, as pybullet does), and limits; none for a held joint, whose gear holds it.
  void make_constraints(const RobotSpec& full, RobotBody& body) const;
  /// Whether joint `j`'s self-locking gear holds it for the coming step, from the State alone
  /// (so a restore holds the same joints): a self-locking position joint standing within
  /// kSelfLockTolerance of its target and moving slower than kSelfLockSpeed. A held joint
  /// reports zero speed, so it stays held until its target moves away.
  static bool holds(const JointSpec& js, const RobotState& s, std::size_t j);
  /// Holds and lets go of a robot's self-locking joints as `holds` says. Nothing is allocated
  /// when nothing changes (every step, nearly always). On a change: a new multibody (Bullet fixes
  /// the degrees of freedom of a multibody when it is made), with the old one's pose and
  /// velocities, a joint taken hold of at rest where it stands and one let go at rest where it was
  /// held; new motors and limits. The colliders stay in the world, and their contacts with them.
  void update_held(std::size_t r, const RobotState& s);
  /// Updates the link colliders' world transforms from the multibody's joint state.
  static void sync_colliders(RobotBody& b);
  /// Pose of a body's frame in the world, from its collider (or the multibody for the base).
  Pose3 body_pose(const RobotBody& b, std::size_t body) const;
  /// Drives each actuated joint toward its target: velocity joints directly, position joints
  /// through a proportional loop on velocity; viscous damping as a joint force against the motion.
  void apply_targets(const RobotSpec& spec, RobotBody& b, const RobotState& s);
  /// A robot's joint states, link poses and base velocity as Bullet holds them (`stepped`: its
  /// motors have solved, so their efforts can be read).
  void read_robot(const RobotSpec& spec, const RobotBody& b, RobotState& s, bool stepped = true) const;

  // physics_groups.cpp
  /// How many groups: `requested`, or with 0 one per 8 robots (up to 32), and a single group
  /// below 8 robots, where splitting gains little (see docs/physics.md). A function of the
  /// scenario alone, never of the machine, so results do not depend on the thread count.
  static int group_count(int requested, int robots);
  /// Puts a robot's multibody, its colliders and its motors and limits into group `g`'s world,
  /// in build order.
  void attach_robot(std::size_t r, int g);
  /// Takes a robot out of its group's world, in reverse build order. Bullet removes by swapping
  /// with the last element, so that taking out the newest first leaves the rest in place.
  void detach_robot(std::size_t r);
  /// Puts rubble body `i` into group `g`'s world.
  void attach_rubble(std::size_t i, int g);
  /// Takes rubble body `i` out of its group's world.
  void detach_rubble(std::size_t i);
  /// Which group each robot (entities 0..R-1) and rubble body (R..R+D-1) belongs in: bodies that
  /// could touch within the next step share a group, and the rest keep a home of their own.
  /// Each body's bounding box is grown by kGroupMargin plus the distance its speed carries it over
  /// four steps; bodies whose grown boxes overlap, directly or through others, form a cluster,
  /// and a cluster lives in group (its lowest entity) mod G. So a robot alone is always in group
  /// r mod G, and the grouping is a function of the bodies' poses and speeds alone: a restore
  /// rebuilds it exactly, and it never depends on the thread count.
  std::pair<std::vector<int>, std::vector<int>> grouping() const;
  /// Moves every body whose group changed into its new group's world: rubble first, then robots,
  /// each in index order (the order they were built in, so one group holds its bodies as the single
  /// world of earlier versions did). A body that moves leaves its contact manifolds behind, and
  /// with them one step's warm start.
  void regroup();
  /// Steps every group's world by dt, each on a worker thread (core/parallel.h): its robots'
  /// targets applied, then their joint states and contacts read back into `state`.
  void step_groups(State& state);

  // physics_contacts.cpp
  /// Names of what touches each robot of group `g` (`members`), and whether a new collision
  /// began. A group's contacts are between its own bodies, so groups can do this side by side.
  void read_contacts(std::size_t g, const std::vector<std::size_t>& members, State& state) const;
  /// What a contact is called: the object's name, or the victim's for any of their body parts.
  std::string name_of(int code) const;
  static std::set<std::string> obstacle_names_of(const World& world);
  /// Counts (and describes the first) body whose pose is non-finite or has left the world by
  /// more than PhysicsOptions::escape_distance: State::trouble.
  void check_trouble(State& state) const;

  // physics_restore.cpp
  /// Puts Bullet's hidden state into the one canonical form that depends only on the bodies'
  /// poses (Bullet's advice for repeatable runs): the bodies are regrouped, then everything is
  /// taken out of every group's world — which frees their broadphase proxies, overlapping pairs
  /// and contact manifolds with the warm-start impulses in them — the then empty broadphase is
  /// reset (tree, ids, staging) and the solver's seed zeroed, and everything goes back in the
  /// order it was built in.
  void canonicalise();
};

}  // namespace rescuesim
