// The crystal's equations of motion, eq. (1): spheres with translation and rotation, contact
// forces of sec. 2.1 (or any contact law: contact/law.hpp), velocity Verlet, periodic x-y box.
// Flat structure of arrays throughout; the contact list is a Verlet list with a skin, rebuilt
// only when a particle has moved more than skin/2, and its per-contact history (the law's
// columns, e.g. tangential spring xi and stick/slip flag) survives rebuilds. Where the Verlet
// list holds pairs apart by more than a margin (a disordered packing), the contact list holds the
// close pairs only, refreshed from the Verlet list's pairs (Dynamics::relist).
//
// Force evaluation is two passes, both free of write conflicts (so OpenMP over contacts and
// over particles gives bit-identical results for any thread count):
//   1. per contact (crystal/kernel.hpp, templated over the law): overlap, normal and tangential
//      force, n x f^t, history, dissipation;
//   2. per particle: sum of its contacts' forces and torques in a fixed order.
// On one thread pass 1 makes the sums of pass 2 itself, in the same order (kernel.hpp's scatter:
// the same bits), and pass 2 only finishes torques and kicks (finish_pass).
#pragma once
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "core/spread_allocator.hpp"
#include "core/error.hpp"
#include "contact/lever_arm.hpp"
#include "crystal/lattice.hpp"
#include "crystal/layer_sums.hpp"
#include "crystal/neighbors.hpp"
#include "crystal/packing.hpp"
#include "crystal/slab.hpp"

namespace granwave::crystal {

// Per-contact arrays, indexed like the pair list.
struct ContactList {
  SpreadVector<std::int32_t> i, j;
  SpreadVector<std::int8_t> image_x, image_y;  // j is taken at x_j + image_x box_x, y_j + image_y box_y (|image| <= 127)
  SpreadVector<double> delta;               // overlap at the last evaluation (<= 0: open); within an advance
                                           // a pass may leave it (ContactPassPlan::list_current)
  SpreadVector<double> f_x, f_y, f_z;       // contact force on i (j gets minus), N (see ContactPassPlan::store_forces);
                                           // empty until a pass or a reader sizes them (keep_forces): +0.0
  // The force columns sized (+0.0) if still empty: a lattice pass keeps its forces by place, and a list
  // whose forces were never asked for needs none (24 bytes a contact).
  void keep_forces() {
    if (f_x.size() != size())
      for (auto* v : {&f_x, &f_y, &f_z}) v->assign(size(), 0.0);
  }
  SpreadVector<double> nf_x, nf_y, nf_z;    // n x f^t (torque on i = -arm_i n x f^t, on j = -arm_j n x f^t);
                                           // threaded runs of a law with torques only (else empty)
  SpreadVector<double> couple_x, couple_y, couple_z;  // a law with couples (rolling, torsion): the torque
                                                     // on i beyond -arm_i n x f^t, j gets minus it (else empty)
  SpreadVector<double> dissipated;          // cumulative dissipated energy since the last rebuild (J)
  // false: every entry of `dissipated` is still the +0.0 of the list's build, so sums of them may be
  // skipped (x + 0.0 = x). Set by a contact pass that may write one (kernel.hpp).
  bool losses_booked = false;
  // The law's history (contact/law.hpp), column by column: history[k * size() + c].
  SpreadVector<double> history;
  std::size_t history_columns = 0;
  double* history_column(std::size_t k) { return history.data() + k * size(); }
  const double* history_column(std::size_t k) const { return history.data() + k * size(); }
  // Per particle p, its contacts in contact order: first those where p is j (i < j, so they come
  // before p's own), j_contacts[j_first[p] .. j_first[p + 1]), then those where p is i, the range
  // i_first[p] .. i_first[p + 1] of the list (sorted by i). The j lists are built at their first
  // use after a list build (j_lists()): a one-thread run, whose contact pass makes the sums, never
  // needs them (28 bytes per particle).
  std::vector<std::int32_t> i_first;
  mutable std::vector<std::int32_t> j_first, j_contacts;
  void j_lists(std::size_t particles) const;
  // Threads: the list cut into `parts` runs of whole blocks of `block` contacts, part q from
  // contact part_begin(..., q), each run scattered into the particles' sums by one thread. A particle
  // that contacts of two parts touch is shared (shared_ends[p] = 1, listed in shared_particles):
  // no part adds to its sums; they are made after the parts join, in contact order. Built by
  // thread_parts at its first use after a list build (and for another number of parts).
  // shared_blocks[b] = 1: block b has a contact of a shared particle, whose values the shared sums read.
  struct ThreadParts {
    int parts = 0;
    std::int64_t block = 0;
    std::vector<std::uint8_t> shared_ends;
    std::vector<std::int32_t> shared_particles;
    std::vector<std::uint8_t> shared_blocks;
    static std::int64_t part_begin(std::int64_t contacts, int parts, std::int64_t block, int q) {
      const std::int64_t blocks = (contacts + block - 1) / block;
      return std::min(contacts, blocks * q / parts * block);
    }
  };
  mutable ThreadParts thread_split;
  const ThreadParts& thread_parts(std::size_t particles, int parts, std::int64_t block) const;
  // Slab decomposition: the contacts [own_first, size()) have their particle i owned by this
  // rank (the list is sorted by i; before own_first, i is a halo particle below). Sums over
  // contacts take these only, so a contact between two ranks counts once. Serial: 0.
  std::size_t own_first = 0;
  std::size_t size() const { return i.size(); }
};

class Dynamics;

// The periodic images' shear and motion beyond the packing's box, for the static probe's box
// strains only (crystal/probe.hpp; all zero in a run): j's image (image_x, image_y) sits at
// x_j + image_x box_x + image_y shift_x, y_j + image_y box_y and, while the box deforms, moves with
// v_j + (image_x rate_x + image_y rate_shift, image_y rate_y, 0), the affine velocity of the image
// offset, so that a tangential spring across the box's faces stretches as one inside it.
struct ImageMotion {
  double shift_x = 0.0;  // m: the x-offset of the +y images (the xy shear of the box)
  double rate_x = 0.0, rate_y = 0.0, rate_shift = 0.0;  // d box_x/dt, d box_y/dt, d shift_x/dt (m/s)
  bool moving() const { return rate_x != 0.0 || rate_y != 0.0 || rate_shift != 0.0; }
  bool any() const { return shift_x != 0.0 || moving(); }
};

// ---- One time step's phases (Dynamics::advance) and what each hands to the next ----

// The half kick and drift's report.
struct Drift {
  bool far = false;         // a particle moved more than skin/2 since the list's build: rebuild
  bool near = false;        // one moved enough to refresh the close pairs (Dynamics::relist)
  bool rows_fresh = false;  // Dynamics::gather_rows hold the drifted state (one thread, no slab)
  // Only the gather rows hold it: the arrays x..wz of particles [0, 4 floor(n/4)) are a step or more
  // behind (Dynamics::state_in_rows) until Dynamics::state_from_rows.
  bool state_in_rows = false;
};
// The next step's finish, half kick and drift made behind a one-thread contact pass (Dynamics::
// finish_behind): the four-particle groups [0, done) and their drift's report.
struct Behind {
  std::int64_t done = 0;
  bool far = false, near = false;
};
// What the contact pass is asked to do.
struct ContactPassPlan {
  double increment_time = 0.0;  // the springs advance by it
  bool rates = true;            // false: a jump of positions (no dashpots)
  bool rows_fresh = false;      // Drift::rows_fresh: the gather rows need no refill
  // Write ContactList::f_x, f_y, f_z and Dynamics::end_arms (the layer stress of a sample reads
  // them); false lets a one-thread pass of a law with torques sum straight into contact_sums.
  bool store_forces = true;
  // Leave the list's overlaps and losses current; false lets a pass leave them until the last step of
  // an advance: the lattice rows' pass keeps its own and brings them in then (the losses before the
  // list is built again), a radius-arm gathered pass stores no overlaps (nothing reads them between).
  bool list_current = true;
  // Not null: finish, kick and drift the particles whose sums are whole behind the pass (one thread:
  // Dynamics::finish_behind), the next step's drift_behind the rest.
  Behind* behind = nullptr;
};
// What the contact pass leaves for the finish: the rows per particle of Dynamics::contact_sums it
// filled (one thread: 1 f, 2 and n x f^t, 3 and delta n x f^t), 0 when the finish sums the
// per-contact arrays (the particle pass); `couples`: one row more after them, the couples' sum.
struct ContactSums {
  int rows = 0;
  bool couples = false;
};

// Where a run's time loop spends its wall time (s), phase by phase. On one thread the finish of
// a step and the next step's half kick and drift are one pass, booked as kick_drift.
struct PhaseTimes {
  enum Phase { kick_drift, halo, list_upkeep, contact_pass, finish, sample, other, kPhases };
  static constexpr std::array<const char*, kPhases> names{"kick_drift",   "halo",   "list_upkeep", "contact_pass",
                                                          "finish",       "sample", "other"};
  std::array<double, kPhases> seconds{};
  double total() const {
    double t = 0.0;
    for (double s : seconds) t += s;
    return t;
  }
};
// One steady_clock read per phase boundary: lap(phase) books the time since the last lap.
class PhaseClock {
 public:
  using Clock = std::chrono::steady_clock;
  PhaseClock(PhaseTimes& times, Clock::time_point start) : times_(times), last_(start) {}
  Clock::time_point lap(PhaseTimes::Phase phase) {
    const Clock::time_point now = Clock::now();
    times_.seconds[phase] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return now;
  }

 private:
  PhaseTimes& times_;
  Clock::time_point last_;
};

// A contact law as the dynamics sees it: crystal/kernel.hpp's LawModel<Law> runs the kernel
// for the law; model_of(law) makes one.
class ContactModel {
 public:
  virtual ~ContactModel() = default;
  virtual std::size_t history_columns() const = 0;
  virtual bool torques() const = 0;      // tangential forces: torques and rotation
  virtual contact::LeverArm lever_arm() const = 0;  // of f^t: a_p - arm_shift(lever_arm()) delta
  virtual bool couples() const { return false; }    // ContactList::couple_x.. (contact::HasCouples)
  // Pass 1 at the current state, as `plan` asks.
  virtual ContactSums contact_pass(Dynamics& dyn, const ContactPassPlan& plan) const = 0;
  // Adds the stored energy (J) of each touching contact of [first, size()) to per_layer[layer of
  // its particle i], in list order (radius: the particles' radii, for laws whose energy depends on them).
  virtual void add_stored_energy(double* per_layer, const ContactList& contacts, std::size_t first,
                                 const int* layer, const double* radius) const = 0;
  // The same sums with the contacts [first, size()) given layer by layer, in list order
  // (Dynamics::LayerOrder::contacts): several layers' sums at once (layer_chains), the same bits;
  // `threaded`: blocks of layers on OpenMP threads, each layer's sum on one (the same bits).
  virtual void add_stored_energy(double* per_layer, const ContactList& contacts, const LayerLists& by_layer,
                                 const double* radius, bool threaded) const = 0;
};

// The law of a case, as its description makes it (contact/case_laws.hpp; crystal/law_models.cpp):
// law = "linear": contact::LinearLuding with friction (k_t > 0 or gamma_t > 0), else the
// frictionless contact::HookeLaw; law = "hertz_mindlin": contact::HertzMindlinLaw (its damping's
// m* from `density`, kg/m^3). Throws InputError for invalid parameters.
std::shared_ptr<const ContactModel> case_model(const contact::LawParams& contact, double density = 0.0);
// rho of the packing's particles, m/((4/3) pi a^3) of the first one (0 for an empty packing).
double packing_density(const Packing& packing);

// The contact list's skin: 0.1 mean radius of the packing (the same on every rank).
double list_skin(const Packing& packing);

class Dynamics {
 public:
  // The packing's fixed particles are not integrated; `dt` is the time step.
  Dynamics(const Packing& packing, const contact::LawParams& contact, double dt);
  // The same with any contact law (crystal/kernel.hpp: model_of(law)). With a slab plan
  // (crystal/slab.hpp), this rank's slab of an MPI run: the state holds the plan's particles
  // [held_lo, held_hi) only, indexed from 0 (local index = global index - offset()), and every
  // global quantity (energies, the rebuild trigger, coordination) is that of the whole crystal.
  // keep_contact_forces false: a sampled step of the lattice pass keeps no per-contact forces for
  // readers of the list (forces_to_list refuses), only what the layer stress sums (LatticeRows::keep_places).
  Dynamics(const Packing& packing, std::shared_ptr<const ContactModel> model, double dt,
           const SlabPlan* slab = nullptr, bool keep_contact_forces = true);

  // ---- state (SoA; public so observers and tests can read and set it) ----
  SpreadVector<double> x, y, z, vx, vy, vz, wx, wy, wz;  // positions (unwrapped), velocities, angular velocities
  SpreadVector<double> fx, fy, fz, tx, ty, tz;           // total force and torque at the current time
  SpreadVector<double> x0, y0, z0;                       // positions of the packing (for displacements)
  SpreadVector<double> radius, mass, inv_mass, inv_inertia, inertia;
  SpreadVector<std::uint8_t> mobile;                     // 1 = integrated
  ContactList contacts;
  // The contact pass's copy of the particle state it reads, as rows of four doubles
  // (crystal/kernel.hpp's gather), refreshed at every pass (or by the one-thread drift, then
  // Drift::rows_fresh): 96 bytes per particle with a law with torques, empty otherwise; each
  // four particles' rows whole cache lines (streams()).
  SpreadVector<double> gather_rows;
  // Per-particle sums of a contact pass that scatters (crystal/kernel.hpp: on one thread, and a
  // law without torques on threads too), rows of four
  // doubles: f, and with a law with torques n x f^t, and with the contact-point arm
  // delta n x f^t, and with a law with couples their sum (each kind a block of 4 size() doubles);
  // read and zeroed by the particle pass. 32 to 128 bytes per particle; empty when a law with
  // torques runs threaded.
  SpreadVector<double> contact_sums;
  // The lever arms times u_z of every contact's ends, (a_i - delta/2) u_z at 2c and (a_j - delta/2)
  // u_z at 2c + 1, +0.0 for an open contact (the layer stress's terms, crystal/simulation.cpp):
  // written with the forces by a one-thread contact pass of a law with torques, while the
  // contact's values are in L1 (then end_arms_stored), so the sample's layer stress needs no walk
  // over the contacts of its own. 16 bytes per contact (the layer stress's scratch otherwise).
  SpreadVector<double> end_arms;
  bool end_arms_stored = false;
  // One end's entry of end_arms: (a - delta/2) u_z, +0.0 for an open contact (delta <= 0), whose
  // force is +0.0, so its terms subtract zeros (x - (+-0) = x for every sum not -0). Both routes
  // (the contact pass's and the layer stress's own) form it here, so they give the same bits.
  static double end_arm(double a, double delta, double u_z) { return delta <= 0.0 ? 0.0 : (a - 0.5 * delta) * u_z; }
  // Whether (a_i + a_j) - delta is the root's distance r bit for bit: delta = reach - r was an
  // exact subtraction while r/2 <= reach <= 2r (Sterbenz), checked with a margin.
  static bool distance_from_overlap_exact(double delta, double reach) {
    return (delta >= -0.5 * reach) & (delta <= 0.25 * reach);
  }
  // The `rows` rows per particle of contact_sums a contact pass fills (all zero on entry).
  double* begin_contact_sums(int rows) {
    contact_sums.resize(4 * static_cast<std::size_t>(rows) * size(), 0.0);
    return contact_sums.data();
  }
  double time = 0.0;
  long steps = 0;
  long rebuilds = 0;  // builds of the Verlet list (a neighbour search each)
  long relists = 0;   // of the close pairs from it (Dynamics::relist)
  double work_in = 0.0;  // cumulative work done by driven particles on the rest (J)

  std::size_t size() const { return x.size(); }
  // Slab decomposition (nullptr: serial). The particles this rank integrates and reports are
  // [own_begin(), own_end()); the others are the halo, copies of the neighbours' boundary
  // layers refreshed by exchange_halo (their forces are incomplete and never used).
  const SlabPlan* slab() const { return slab_.get(); }
  std::size_t offset() const { return offset_; }
  std::size_t own_begin() const { return own_lo_; }
  std::size_t own_end() const { return own_hi_; }
  // Copies the neighbours' boundary layers (positions, velocities, angular velocities with a
  // law with torques: what contact::Contact reads of a particle) into the halo. Serial: no-op.
  void exchange_halo();
  // The packing's lattice and per-particle layer and fixed flags (of the held particles, by
  // local index); its positions, radii, masses and inertias are not kept twice: read x0, y0,
  // z0, radius, mass, inertia.
  const Packing& packing() const { return packing_; }
  double dt() const { return dt_; }
  void set_dt(double dt) { dt_ = dt; }
  const ContactModel& model() const { return *model_; }
  // The periodic box (packing().box_x, box_y) and its images' shear and motion (ImageMotion): the
  // static probe's box strains; images keep their indices. The image velocity enters the contact
  // pass of a law with torques (the one with tangential springs); a law without reads positions
  // only, its dashpot no image velocity. Refused under a slab plan.
  void set_box(double box_x, double box_y, const ImageMotion& images);
  const ImageMotion& images() const { return images_; }
  // The law has tangential forces: torques, rotation (angular velocities in the halo and the rows).
  bool torques() const { return torques_; }
  // Lever arm of f^t (contact/lever_arm.hpp): arm_i = a_i - arm_shift(lever_arm()) delta.
  contact::LeverArm lever_arm() const { return lever_arm_; }

  // Start (or stop) integrating particle p (velocity drive makes the source mobile).
  void set_mobile(std::size_t p, bool on);
  // The same for a set of particles (local indices), with one list rebuild; under a slab plan
  // every rank calls it together, with the particles it holds (possibly none).
  void set_mobile(const std::vector<std::size_t>& which, bool on);
  // Rigid step of the particles in `which` by (dx, dy, dz), held afterwards: the contacts are
  // updated statically (normal overlaps only: a jump does not stretch the tangential springs, so
  // f_t = 0 at t = 0 as in seed 002; no dashpot) and the change of stored plus dissipated energy
  // is booked as work_in.
  void displace(const std::vector<std::size_t>& which, double dx, double dy, double dz);
  // Recompute the contact list from scratch (keeps history of pairs that persist).
  void rebuild();
  // A wider Verlet skin and the close pairs' `margin` from now on, the list built again: fewer builds
  // and relists where particles travel far (a relaxation's FIRE steps); the same forces and sums, bit
  // for bit (list_margin below). A skin at most today's changes nothing; not finite or <= 0: refused.
  void widen_skin(double skin, double margin);
  double skin() const { return skin_; }
  // The close pairs (the margin below) again from the Verlet list's pairs, without a neighbour
  // search (keeps history and losses of the pairs that persist; not a rebuild: `rebuilds` counts
  // the Verlet list's builds, as LAMMPS counts its neighbour lists).
  void relist();
  // The contact list holds the Verlet list's pairs (i, j) that were closer than
  // a_i + a_j + list_margin() at its build, and every pair with a history or a loss: no other can
  // touch before a particle has moved 3/8 list_margin() (relist then). The same forces and sums as
  // the whole Verlet list, bit for bit: a pair left out is open, its force, history and loss zero,
  // and every sum over contacts starts from +0.0, so adding its zeros changes nothing. Default
  // close_margin_share of the skin; at skin or more, or in a sheared or moving box, or under a slab
  // plan: every pair.
  void set_list_margin(double margin);
  // A wave moves particles a small part of a radius: on the disordered row (20 000 spheres) the
  // contact list holds 2 % open pairs at skin/16 against 6 % at skin/4, and relists none
  // (docs/benchmarks.md, session 42).
  static constexpr double close_margin_share = 1.0 / 16.0;
  double list_margin() const { return list_margin_; }
  std::size_t verlet_pairs() const { return candidates_.size() ? candidates_.size() : contacts.size(); }
  // A frictional prepared packing's springs (Packing::springs) into the history of the listed pairs:
  // the first three columns, the spring xi of the laws whose history is the displacement.
  void seed_springs(const std::vector<packing::SpringHistory>& springs);
  // Forces and torques at the current positions and velocities (advances springs by v_t dt).
  void compute_forces() { compute_forces(dt_, true); }
  // The same for a state set from outside (initial velocities): dashpots see the velocities,
  // springs are not advanced (no time has passed).
  void compute_forces_of_state() { compute_forces(0.0, true); }
  // One velocity-Verlet step of translation and rotation (store_forces: ContactPassPlan's).
  void step(bool store_forces = true) { advance(1, store_forces); }
  // k steps, the same as k calls of step(), bit for bit; the last one stores the contact forces
  // when `store_forces`. Each step's phases, in order, each booked to `clock` (if any):
  // half_kick_drift, exchange_halo (slab), upkeep_list, the model's contact_pass, finish_step.
  // Without a slab, when the contact pass made the sums (one thread; a law without torques on
  // threads too), the finish and second half kick of each step but the last and the first half
  // kick and drift of the next are one pass over the particles (finish_kick_drift):
  // forces and torques fx..tz are current only when advance returns.
  void advance(long k, bool store_forces = true, PhaseClock* clock = nullptr);

  // The lattice rows of the contact pass (crystal/lattice.hpp) when the held particles are such a
  // crystal, the box neither sheared nor moving and the list the lattice's; else nullptr (the list's
  // pass). Mapped again after each build of the list.
  LatticeRows* lattice_rows();
  // A lattice pass keeps a sampled step's contact forces and end arms by slot (LatticeRows::place_f_x):
  // a reader of contacts.f_x, f_y, f_z or end_arms calls forces_to_list() first (then they are the last
  // sampled step's, as the list's pass leaves them, and sized: ContactList::keep_forces). The layer
  // stress reads them where they are: sampled_lattice_forces() (nullptr: in the list) with place_ends(),
  // LayerOrder::ends by place.
  void forces_to_list() const;
  // Everything the lattice rows hold for the list (losses, forces): before a build or the list's pass.
  void lattice_to_list();
  const LatticeRows* sampled_lattice_forces() const;
  // The layer stress the last pass summed (LatticeRows::stress_fresh) while nothing newer holds it.
  const LatticeRows* sampled_lattice_stress() const;
  const LayerLists& place_ends(std::int32_t span = 0) const;
  // false: the list's pass for such a crystal too (its sums in the list's order: other bits; the
  // tests' and benches' second route).
  bool lattice_pass = true;
  // OpenMP is used from this many particles on (fork/join costs more than it saves on small
  // crystals, and much more on a loaded machine), and only when OpenMP may run more than one
  // thread (else the one-thread route, which sums forces in the contact pass, is faster);
  // results do not depend on it.
  std::size_t parallel_min_particles = 20000;
  bool threaded() const { return size() >= parallel_min_particles && threads_available() > 1; }
  static int threads_available();  // omp_get_max_threads(); 1 without OpenMP
  // From this many particles on, what a step writes whole for a later pass to read -- the gather
  // rows of the kick and drift, the forces and end arms a sampled step stores -- goes past the
  // caches (simd::stream4): the step then streams more than the L3 holds before it is read back,
  // and a plain store would first read each line from memory. Results do not depend on it.
  std::size_t stream_min_particles = 65536;
  bool streams() const { return size() >= stream_min_particles; }
  // From this many particles on, up to those that stream (one thread, no slab), the gather rows are
  // the state within an advance: the fused particle pass reads x, v and w from the rows it wrote the
  // step before and writes only the rows, and the arrays are made from the rows where something reads
  // them (the list's upkeep, the advance's last step). Beyond the L2 that takes a fifth off the pass;
  // in it the transposes cost more than they save, and from memory (streams()) it gains nothing
  // (docs/benchmarks.md, session 59). Results do not depend on it.
  std::size_t state_in_rows_min_particles = 8192;
  bool state_in_rows() const {
    return size() >= state_in_rows_min_particles && !streams() && !slab_ && !threaded();
  }
  // Where the rows are the state, the next step's finish, half kick and drift run behind the one-thread
  // contact pass, at least this many particles at a time once their sums are whole (the list is sorted
  // by i with i < j), while their rows and sums are still in the L2: the disordered row's loop 0.93-0.95
  // (docs/benchmarks.md, session 60); 0: after the pass. Results do not depend on it.
  std::size_t behind_batch = 4096;
  bool finishes_behind() const;
  // The four-particle groups below `below` (rounded down) not yet done, once at least behind_batch
  // particles or the last of them wait; `sums`: the layout of the contact pass's sums.
  void finish_behind(Behind& behind, const ContactSums& sums, std::int64_t below);

  // ---- energies (J) ----
  // Each is a sum per layer (particles in index order, contacts in list order counted in the
  // layer of their particle i), then over the layers in layer order: the same bits for any
  // number of ranks (docs/design.md §2.8).
  double kinetic_energy() const;    // translational + rotational, mobile particles
  // The law's stored energy over touching contacts (ContactModel::add_stored_energy): normal,
  // (1/2) k delta^2 for the linear law, (2/5) k delta^(5/2) for Hertz (f_n = k delta^(3/2),
  // k = (4/3) E* sqrt(R*)); plus (1/2) k_t |xi|^2 of a tangential spring (Mindlin: k_t of delta).
  double potential_energy() const;
  double dissipated_energy() const; // cumulative: dashpots, sliding, springs lost on opening
  // dt^2/8 sum(|F|^2/m + |T|^2/I): velocity Verlet conserves E_kin + E_pot minus this exactly
  // for linear forces (the "shadow" energy), so it separates integrator error from physics.
  double verlet_correction() const;
  // The four at once (one message under a slab plan; the same bits).
  struct Energies {
    double kinetic = 0.0, potential = 0.0, dissipated = 0.0, verlet_correction = 0.0;
  };
  Energies energies() const;
  int touching_contacts_of(std::size_t p) const;
  // The orders of the per-layer sums (docs/design.md §2.8) as lists for layer_chains, made at
  // the first call after each rebuild of the contact list.
  struct LayerOrder {
    LayerLists particles;  // the owned particles by layer, in index order
    LayerLists contacts;   // the contacts [own_first, size()) by the layer of i, in list order
    // The ends of every contact not between two fixed particles, 2c (particle i) and 2c + 1
    // (particle j), by the layer of that particle, in list order, i before j (the layer stress).
    LayerLists ends;
    // Per contact: how many of its two particles are owned and not fixed (coordination).
    std::vector<std::uint8_t> counted_ends;
    long free_particles = 0;  // owned, not fixed
  };
  const LayerOrder& layer_order() const;
  double max_displacement_since_build() const;

 private:
  void compute_forces(double increment_time, bool dashpots, bool kick = false);  // kick: then v += F dt/2m
  // Pass 2 after the contact pass, from what the pass left.
  void finish_forces(const ContactSums& sums, bool kick);
  // The first half kick and drift, after the finish of the step before when its sums `waiting`
  // were left for it (one thread: finish_kick_drift).
  Drift half_kick_drift(const ContactSums& waiting);
  // The same when the contact pass made part of it behind it: the groups it left, then the tail.
  Drift drift_behind(const ContactSums& waiting, const Behind& behind);
  // Contact-list upkeep: a rebuild when the drift took a particle out of its skin (under a slab
  // plan, when it did on any rank).
  void upkeep_list(const Drift& drift);
  // The step's finish and second half kick from the contact pass's `sums`; returns them instead,
  // left for the next step's half_kick_drift, when it can take them (sums made, no slab, not
  // the `last` step), else an empty ContactSums.
  ContactSums finish_step(const ContactSums& sums, bool last);
  // The first half kick and drift of the owned particles from `from` on (-1: all)
  template <bool Torques, bool Threaded>
  Drift kick_drift(std::int64_t from = -1);
  template <bool Kick, bool Torques, bool ContactPointArm, bool Threaded, bool Couples>
  void particle_pass(double h);  // pass 2 over the owned particles, h: the half kick (0: none)
  template <bool Kick, int Rows, bool Couples>
  void finish_pass(double h, std::int64_t from = -1);  // pass 2 from contact_sums (threaded when from < 0), from `from` on
  // finish_pass<true, Rows, Couples>, then kick_drift, four particles at a time, from particle q0 (a
  // multiple of four) to the end; with q1 >= 0 only the groups [q0, q1) from the gather rows
  // (finish_behind). The second form takes Rows and Couples from the sums' layout.
  template <int Rows, bool Couples>
  Drift finish_kick_drift(std::int64_t q0, std::int64_t q1);
  Drift finish_kick_drift(const ContactSums& sums, std::int64_t q0, std::int64_t q1);
  void state_from_rows();     // x..wz of particles [0, 4 floor(n/4)) from the gather rows (Drift::state_in_rows)
  // Per-layer sums of the owned particles (contacts [own_first, size())), added to s[layer].
  // Kinetic and/or Verlet (nullptr: not wanted), through layer_order().
  void add_particle_energies(double* kinetic, double* verlet) const;
  void add_dissipated(double* s) const;  // of `contacts`, through layer_order()
  void add_dissipated(double* s, const ContactList& list) const;  // any list (the old one at a rebuild)
  // The totals of `k` per-layer arrays (each packing().layers long): under a slab plan every
  // rank first receives the other ranks' layers; then each array's layers are added in order.
  void layer_totals(std::vector<double>* arrays, std::size_t k, double* totals) const;
  void check_layers() const;  // slab: every owned particle within z_tolerance of its layer

  Packing packing_;
  LatticeRows lattice_;
  int lattice_layout_ = 0;  // 1: lattice_ laid out, -1: not a lattice crystal (or no longer), 0: not yet asked
  std::shared_ptr<const ContactModel> model_;
  bool torques_ = false;
  bool couples_ = false;  // the model's couples(): the particle pass sums them
  contact::LeverArm lever_arm_ = contact::LeverArm::radius;
  ImageMotion images_;
  double dt_ = 0.0;
  void take_skin(double skin);  // skin_ and far2_
  double skin_ = 0.0;
  double far2_ = 0.0;  // a particle is more than skin/2 from its place at the build when d^2 > far2_
  // The close pairs (set_list_margin): the Verlet list's pairs while the contact list holds fewer
  // (else empty); relist when a particle's squared displacement since the build exceeds near2_
  // (+inf: the contact list is the whole Verlet list).
  PairList candidates_;
  double list_margin_ = 0.0;
  double near2_ = std::numeric_limits<double>::infinity();
  // Displacements from x0 at the last relist, as x_build_ (empty until one: x_build_ then).
  SpreadVector<float> x_relist_, y_relist_, z_relist_;
  const SpreadVector<float>& relist_x() const { return x_relist_.empty() ? x_build_ : x_relist_; }
  const SpreadVector<float>& relist_y() const { return y_relist_.empty() ? y_build_ : y_relist_; }
  const SpreadVector<float>& relist_z() const { return z_relist_.empty() ? z_build_ : z_relist_; }
  void make_list(bool verlet_build);  // the contact list from candidates_ (rebuild, relist)
  // The largest |(x - x0) - r|^2 of the owned particles (this rank's), r a kept displacement.
  double max_displacement2_from(const SpreadVector<float>& rx, const SpreadVector<float>& ry,
                                const SpreadVector<float>& rz) const;
  // x - x0 of every held particle into rx, ry, rz, in single precision (a list's reference).
  void keep_displacements(SpreadVector<float>& rx, SpreadVector<float>& ry, SpreadVector<float>& rz) const;
  void relist_if_moved();             // relist when a particle moved as far as near2_ allows
  std::vector<double> dissipated_before_;  // per layer, folded in at rebuilds
  long list_builds_ = 0;                   // rebuilds of the contact list so far
  mutable LayerOrder order_;               // layer_order() of the list build order_build_
  mutable long order_build_ = -1;
  mutable LayerLists place_ends_;        // place_ends() of the list build place_ends_build_
  mutable long place_ends_build_ = -1;
  mutable std::int32_t place_ends_span_ = 0;
  std::shared_ptr<const SlabPlan> slab_;
  std::size_t offset_ = 0, own_lo_ = 0, own_hi_ = 0;
  std::size_t halo_below_ = 0, halo_above_ = 0;  // particles sent to (and received from) each side
  std::vector<double> send_below_, recv_below_, send_above_, recv_above_;
  // Displacements from x0 at the last list build, in single precision (memory): the skin test
  // needs them to ~1e-13 m, float gives 6e-8 of a displacement.
  SpreadVector<float> x_build_, y_build_, z_build_;
};

// Frictionless relaxation of a packing (FIRE, Bitzek et al. 2006, on the mobile particles; the
// fixed layers stay): stops when E_kin/E_pot < tolerance has held for the last 50 steps.
// Velocities are zero afterwards. Returns the number of steps; throws NotStanding if the contacts
// open (the packing is unjammed without friction), RunError if it does not converge within max_steps.
struct RelaxResult {
  long steps = 0;
  double ratio = 0.0;
};
// The relaxation lost the packing: its contact energy fell below kNotStanding of the start (or there was
// none), so without friction nothing holds it (a loose or friction-prepared packing).
inline constexpr double kNotStanding = 1e-6;
struct NotStanding : RunError {
  NotStanding(double e_start, double e_now, long steps)
      : RunError("the packing does not stand without friction: frictionless relaxation took its contact energy from " +
                 energy(e_start) + " to " + energy(e_now) + " in " + std::to_string(steps) + " steps"),
        e_start(e_start), e_now(e_now), steps(steps) {}
  static std::string energy(double e) {
    char s[32];
    std::snprintf(s, sizeof s, "%.3g J", e);
    return s;
  }
  double e_start, e_now;
  long steps;
};
// With the case's law, frictionless and undamped (its description's relaxation: Hertz, the time step
// from k_n at the largest initial overlap).
RelaxResult relax(Packing& packing, const contact::LawParams& contact, double density, double tolerance,
                  long max_steps = 2000000);
// FIRE with `model` (frictionless and undamped), whose stiffest contact has the contact time t_c.
RelaxResult relax_with(Packing& packing, std::shared_ptr<const ContactModel> model, double t_c, double tolerance,
                       long max_steps = 2000000);

}  // namespace granwave::crystal
