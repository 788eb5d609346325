#pragma once

#include <coshell/contact/barrier.h>
#include <coshell/contact/ccd.h>
#include <coshell/contact/contact_potential.h>
#include <coshell/contact/distances.h>
#include <coshell/contact/obstacle.h>
#include <coshell/model/contribution.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/shell_state.h>

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/numerics/rtree.h>

#include <array>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace coshell::contact
{
  enum class Method
  {
    none,    ///< no contact: nothing is built
    barrier, ///< IPC log barrier with a collision-free step filter
    penalty  ///< smoothed penalty on the penetration
  };

  /// prm subsection "Contact".
  struct ContactParameters
  {
    Method method = Method::none;
    /// Barrier: gap below which the barrier acts (length); 0 = automatic.
    double activation_distance = 0;
    /// Barrier (N/mm^3 in mm, N; energy per area per length^2); 0 = auto.
    double barrier_stiffness = 0;
    /// Automatic barrier stiffness from the dead load instead of E / h.
    bool barrier_stiffness_from_load = false;
    /// Penalty: pressure per penetration (N/mm^3); 0 = automatic.
    double penalty_stiffness = 0;
    /// Penalty: penetration over which the penalty's stiffness ramps up.
    double penalty_smoothing = 0;
    /// Penalty: 0, or the fraction of each pair's offset that the step
    /// filter keeps the pair apart (dimensionless, below 1).
    double penalty_step_filter = 0;
    /// A step whose smallest gap falls below this fraction of the
    /// activation distance doubles the barrier stiffness (dimensionless).
    double stiffening_gap_ratio = 1e-3;
    bool   project_tangent      = true;
    /// Project the Hessians while retrying a failed step.
    bool project_tangent_on_retry = false;
    /// Project the Hessians for the rest of a step once a Newton
    /// correction has climbed the energy.
    bool project_tangent_on_stall = false;
    /// Keep only pairs whose distance is a local minimum over the surface.
    bool local_minima_only = false;
    /// Friction: tangential speed below which friction is smoothed (the
    /// creep speed of sticking), length / s.
    double stiction_velocity = 1e-3;
    /// Friction: the least smoothing length of a step, whatever its
    /// duration (length; 0: v_s dt alone).
    double stiction_displacement = 0;
    /// Shell edges against obstacle edges (with IPC's mollifier for
    /// nearly parallel edges), with the obstacle's friction.
    bool edge_edge_pairs = true;
    /// Shell against shell (vertex-triangle pairs, and edge-edge pairs
    /// with edge_edge_pairs).
    bool self_contact = false;
    /// Coulomb coefficient of the shell against itself (dimensionless).
    double self_friction_coefficient = 0;
    /// Pairs of one connected piece closer than this multiple of their
    /// offset in the reference configuration are not self-contact pairs.
    double                self_exclusion = 2;
    std::vector<Obstacle> obstacles;

    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const std::string        &prm_directory);
    bool        enabled() const
    {
      return method != Method::none;
    }
  };

  /// The force and moment (about the origin) that the shell exerts on an
  /// obstacle, and its number of active contact pairs.
  struct ObstacleLoad
  {
    dealii::Tensor<1, 3> force, moment;
    unsigned int         active_pairs = 0;
  };

  /// Contact of the shell's mid-surface with rigid obstacles, kept at
  /// least half the shell thickness plus the obstacle's offset apart.
  /// Pairs are shell vertices against obstacle triangles and obstacle
  /// vertices against shell triangles. Obstacles move to their position
  /// at the evaluation time as far as the step filter lets them, so that
  /// no iterate interpenetrates (barrier). Lives across the stages.
  class Contact
  {
  public:
    /// 'load_pressure': the mean dead load per area of the shell (N/mm^2),
    /// used by Barrier stiffness scale = load.
    Contact(const model::ShellModel &model,
            const ContactParameters &parameters,
            double                   load_pressure = 0);

    /// Throws, naming the obstacle and the shell vertex or triangle, if the
    /// shell at 'time' is closer to an obstacle than its offset.
    void check_initial_configuration(const model::ShellState &state,
                                     double                   time);

    void   prepare(const model::ShellState &state, double time);
    bool   obstacles_pending() const;
    void   add_pair_terms(const model::ShellState &state,
                          const model::BlockSink  &sink,
                          bool                     with_tangent);
    double admissible_fraction(const model::ShellState      &state,
                               const dealii::Vector<double> &correction) const;
    /// Ends a step: the step's state becomes the one to restore, and the
    /// obstacles' work is brought up to date.
    void save();
    void restore();

    /// Named arrays of the state a restart needs, as save() will leave it
    /// after the current, converged step (obstacle positions, which may lag
    /// behind their motion, the barrier stiffness, the works and forces of
    /// the energy bookkeeping, friction's lagged normal forces); and the
    /// way back from them at 'time' with the shell in 'state'
    /// (contact_checkpoint.cc). Throws std::invalid_argument on arrays of
    /// another scene.
    std::map<std::string, std::vector<double>> checkpoint_arrays() const;
    void                                       restore_checkpoint_arrays(
                                              const std::map<std::string, std::vector<double>> &arrays,
                                              const model::ShellState                          &state,
                                              double                                            time);
    /// Line search: the obstacles' positions before a trial evaluation,
    /// put back after it (a trial advances them against a shell shape
    /// that is then undone, which could leave them inside the shell).
    void begin_trial();
    void end_trial();
    bool self_contact() const
    {
      return parameters_.self_contact;
    }
    /// Self-contact pairs with a force at the last evaluation.
    unsigned int self_active_pairs() const
    {
      return self_active_pairs_;
    }
    /// Vertex pairs that self contact may couple during the next step:
    /// those within reach plus a margin of the largest thickness. Found
    /// anew only once the shell has moved a quarter of that margin, less
    /// a common translation, since they were last found (before, the
    /// same list), so the pattern keeps half its margin for the step.
    /// Brings the list up to date; returns its generation, which changes
    /// each time the list is found anew (0 without self contact).
    std::uint64_t update_self_couplings(const model::ShellState &state) const;
    /// The list of the last update_self_couplings().
    const std::vector<std::array<unsigned int, 2>> &self_couplings() const
    {
      return coupling_pairs_;
    }

    /// Per obstacle, at the last evaluation.
    const std::vector<ObstacleLoad> &obstacle_loads() const;
    /// Follow the load slopes of every obstacle from the next tangent on
    /// (a linearized step needs them to carry its reported loads to the
    /// step's end, see extrapolate_loads()).
    void follow_force_slopes();
    /// d(force or moment component 'axis')/d(shell DoFs) of an obstacle,
    /// DoF layout (empty for an obstacle not followed).
    dealii::Vector<double>
    load_gradient(unsigned int obstacle, unsigned int axis, bool moment) const;
    /// For an obstacle that an interactive input drives (its Input
    /// direction d, the input s moving it by s d): its force slopes along
    /// e = d / |d|. The force F the shell exerts on the obstacle along e
    /// has dF/d(shell) = 'coupling' and, with the shell held, dF/ds = -|d|
    /// 'stiffness'; the shell's residual has dr/ds = |d| 'coupling'.
    /// Empty 'coupling' for the other obstacles.
    struct InputCoupling
    {
      dealii::Vector<double> coupling;      ///< H_ss e, DoF layout, N/length
      double                 stiffness = 0; ///< e^T H_ss e, N/length
    };
    InputCoupling input_coupling(unsigned int obstacle) const;
    /// A linearized step ends without evaluating at its end: the loads
    /// of the last evaluation (force and moment), on the obstacles whose
    /// slopes are followed, become their linearization at the
    /// configuration moved by 'correction' (DoF layout),
    /// F + (dF/d shell) correction. The works and gaps stay those of the
    /// evaluation.
    void extrapolate_loads(const dealii::Vector<double> &correction);
    /// While true, the tangent's pair Hessians are not projected to
    /// positive semi-definite whatever Projected tangent says: the slope
    /// of a driven obstacle's force is exact only with the exact tangent.
    void set_exact_tangent(bool exact)
    {
      exact_tangent_ = exact;
    }
    /// Per obstacle, the work its prescribed motion has done on the shell
    /// up to the last evaluation, N mm: the change of its pairs' energy
    /// plus the work of their force on the shell (see step_work()). This
    /// is the energy a plunger puts in; a fixed obstacle puts in none
    /// beyond what friction on it dissipates (negative).
    std::vector<double> obstacle_work() const;
    /// How far obstacle o's centroid has moved since time 0 (as far as
    /// the step filter has let it), length.
    dealii::Tensor<1, 3> obstacle_displacement(unsigned int o) const;
    /// The barrier (or penalty) energy of every pair at the last
    /// evaluation, N mm: the energy contact stores, which the balance of
    /// a scene's energies must count.
    double potential() const;
    /// Friction's dissipation over the step since save() (energy), at the
    /// last evaluation.
    double step_friction_dissipation() const
    {
      return friction_dissipation_;
    }
    const std::vector<Obstacle> &obstacles() const;
    /// Smallest gap (distance minus offsets) over every evaluation since
    /// the last save() (+inf if no pair was within reach), length.
    double smallest_gap() const;
    /// The same of obstacle o's pairs alone, and of the self-contact pairs
    /// alone: smallest_gap() is the least of these.
    double smallest_obstacle_gap(unsigned int o) const;
    double smallest_self_gap() const;
    /// Largest penetration (penalty) since the last save(), length.
    double largest_penetration() const;
    /// Vertex fields in the DoF layout: contact force (ux..uz slots), the
    /// smallest gap of the vertex's pairs (rx slot, +inf -> activation
    /// distance) and the contact pressure |f| / area (ry slot).
    dealii::Vector<double> vertex_fields() const;
    /// Writes the obstacles at their current positions as one VTU file.
    void write_obstacles_vtu(const std::string &file) const;
    /// For a failed solve's message, from the pairs of the last
    /// evaluation: the shell vertex squeezed hardest between two
    /// obstacles (both gaps below a tenth of the activation distance), or
    /// else the smallest gap and its obstacle; "" without pairs.
    std::string squeeze_report() const;
    /// For the same message, with friction: its pairs and the smoothing
    /// length of sticking this step; "" without friction.
    std::string friction_report() const;
    /// With exact pair Hessians and Projected tangent on stall: project
    /// them until the step is accepted or undone. True if that changed
    /// the tangent.
    bool   use_projected_tangent();
    double barrier_stiffness() const;
    /// Wall-clock seconds so far: pair detection (and obstacle moves),
    /// pair forces and stiffness, collision filter of the corrections;
    /// tree_build, the R-trees of the obstacles (when they move) and of
    /// the shell's triangles, is part of detection and filter.
    struct Timing
    {
      double detection = 0, pair_terms = 0, filter = 0, tree_build = 0;
    };
    const Timing &timing() const;
    double        activation_distance() const;

  private:
    /// The slopes of an obstacle's load, for an obstacle whose load is
    /// followed (see follow_force_slopes(); an interactive input's driven
    /// obstacles always are), at the last evaluation that assembled the
    /// tangent, from its contact and friction pairs' exact (not projected)
    /// Hessians: how the force F and the moment M (about the origin) that
    /// the shell exerts on the obstacle change with each shell DoF. The
    /// pairs' energies depend on differences of positions only, so the
    /// shell's blocks H_ss also stand for the obstacle's: with the shell
    /// held, dF_k/d(obstacle translation along axis l) = -stiffness[k][l].
    struct ForceSlopes
    {
      bool followed = false;
      /// dF/du_dof and dM/du_dof of one pair, N/length and N; a DoF may
      /// appear in several entries, which add.
      struct Entry
      {
        dealii::types::global_dof_index dof;
        dealii::Tensor<1, 3>            force, moment;
      };
      std::vector<Entry> entries;
      /// e_k^T H_ss e_l summed over the pairs, N/length.
      dealii::Tensor<2, 3> stiffness;
    };
    /// A shell vertex against an obstacle triangle (shell_vertex_side), or
    /// an obstacle vertex against a shell triangle.
    /// A self-contact pair is a shell vertex ('shell') against a shell
    /// triangle ('other'); shell_vertex_side is true, 'obstacle' unused.
    /// An edge-edge pair is a shell edge ('shell', into shell_edges_)
    /// against an obstacle edge ('other', into obstacle_edges_).
    struct Pair
    {
      bool         shell_vertex_side = true;
      unsigned int obstacle          = 0;
      unsigned int shell             = 0; ///< shell vertex or triangle index
      unsigned int other             = 0; ///< obstacle triangle or vertex
      double       area      = 0; ///< the pair's share of the shell, length^2
      bool         self      = false;
      bool         edge_edge = false;
      /// The distance the pair search found (length), at the positions
      /// add_pair_terms() evaluates the pair at: there it tells the pairs
      /// that carry no force from the rest before their points and
      /// distance derivatives are made again. Not kept in checkpoints.
      double searched_distance = 0;
    };
    /// Which of a pair's 12 coordinates are the shell's: [first, last).
    struct ShellCoordinates
    {
      unsigned int first, last;
    };
    static ShellCoordinates shell_coordinates(const Pair &pair);
    /// Whether point k (0..3) of the pair lies on its obstacle.
    static bool on_obstacle(const Pair &pair, unsigned int k);
    /// The pair's distance function (point-triangle or segment-segment).
    static SquaredDistance pair_distance(const Pair                    &pair,
                                         const std::array<Point<3>, 4> &p,
                                         bool derivatives);
    /// The pair's energy weight * m * phi(gap) as a function of its 12
    /// coordinates (m: the edge-edge mollifier, 1 otherwise): gradient
    /// and Hessian.
    struct PairEnergy
    {
      double        value     = 0;
      double        mollifier = 1; ///< m: the normal force is w m |phi'|
      Coordinates12 gradient{};
      Matrix12      hessian{};
    };
    /// What friction keeps of a pair from the last converged state.
    struct NormalForce
    {
      Pair                  pair;
      double                force; ///< normal force, N
      std::array<double, 2> closest;
      dealii::Tensor<1, 3>  normal; ///< from the closest point to the point
    };
    std::vector<NormalForce> normal_forces_;
    std::vector<NormalForce> lagged_normal_forces_;
    using Tree = dealii::RTree<std::pair<dealii::BoundingBox<3>, unsigned>>;

    const model::ShellModel &model_;
    ContactParameters        parameters_;
    /// Cell thickness of each shell triangle, and the largest one.
    std::vector<double> shell_triangle_thickness_;
    double              largest_thickness_ = 0;
    /// self_couplings(): where the shell was when they were found.
    mutable std::vector<dealii::Point<3>>            coupling_positions_;
    mutable std::vector<std::array<unsigned int, 2>> coupling_pairs_;
    mutable std::uint64_t                            coupling_generation_ = 0;
    /// kappa_: the barrier stiffness, which save() doubles when the
    /// potential stiffens; made and checkpointed for the penalty too, so
    /// that the checkpoint and the summary keep one layout. activation_:
    /// the barrier's activation distance, also the scale of the gap
    /// output and of the squeeze report for either method.
    double kappa_ = 0, activation_ = 0;
    /// The pair potential of parameters_.method, made once.
    std::unique_ptr<ContactPotential>    pair_potential_;
    std::vector<unsigned int>            shell_vertices_; ///< used
    std::vector<double>                  shell_vertex_area_;
    std::vector<std::array<unsigned, 3>> shell_triangles_;
    std::vector<double>                  shell_triangle_area_;
    /// Shell edges (sorted vertex pairs), their share of the shell area
    /// (a third of each triangle they bound) and squared reference length.
    std::vector<std::array<unsigned, 2>> shell_edges_;
    std::vector<double>                  shell_edge_area_;
    std::vector<double>                  shell_edge_length2_;
    /// The three edges of each shell triangle; per shell edge, the sorted
    /// shell edges it does not pair with in self contact.
    std::vector<std::array<unsigned, 3>> shell_triangle_edges_;
    std::vector<std::vector<unsigned>>   excluded_edges_;
    /// Per obstacle: its edges, and the three edges of each triangle.
    std::vector<std::vector<std::array<unsigned, 2>>> obstacle_edges_;
    std::vector<std::vector<std::array<unsigned, 3>>> obstacle_triangle_edges_;
    double                                            target_time_ = -1e300;
    /// Each obstacle's friction coefficient at target_time_.
    std::vector<double>                        obstacle_friction_;
    std::vector<std::vector<dealii::Point<3>>> current_, saved_, target_;
    /// Each obstacle's tree where it is now (current_), built by
    /// obstacle_tree() when a search first needs it after the obstacle
    /// moved: a moving obstacle (the plunger) moves at every evaluation,
    /// while the candidate lists that search the tree are kept over many
    /// steps (building it at each move would show in every haptic
    /// step).
    mutable std::vector<std::optional<Tree>> obstacle_trees_;
    /// How often each obstacle's positions have changed (from 1): a list
    /// made at a count still current saw the same positions, and the
    /// drifts need not be summed over the obstacle's vertices (a still
    /// cartridge has thousands, summed at every evaluation).
    std::vector<std::uint64_t>    obstacle_moves_;
    std::vector<Pair>             pairs_;
    std::vector<dealii::Point<3>> positions_;       ///< shell, at prepare()
    std::vector<dealii::Point<3>> saved_positions_; ///< at save()
    double                        saved_time_ = 0;
    std::vector<ObstacleLoad>     loads_;
    std::vector<ForceSlopes>      force_slopes_;
    /// Whether the last evaluation assembled the tangent, and with it the
    /// force slopes.
    bool                slopes_at_last_evaluation_ = false;
    std::vector<double> obstacle_work_; ///< up to save()
    /// Per obstacle, its pairs' energy and their force on the shell (DoF
    /// layout), at the last evaluation and at save().
    std::vector<double> potential_per_obstacle_;
    std::vector<double> saved_potential_per_obstacle_;
    /// The friction dissipated since save(), mu lambda f0(|u|) summed over
    /// the lagged pairs, per obstacle and in all (self pairs included), at
    /// the last evaluation.
    std::vector<double>                 friction_dissipation_per_obstacle_;
    double                              friction_dissipation_ = 0;
    std::vector<dealii::Vector<double>> shell_force_, saved_shell_force_;
    std::vector<dealii::Point<3>>       start_centroids_; ///< at time 0
    double                              potential_ = 0;
    std::vector<double>                 vertex_gap_;
    /// Element/Thickness stretch: h / h0 of each shell vertex at the last
    /// prepare() (empty without it: every offset is the reference's), and
    /// the largest one (at least 1).
    std::vector<double>    stretch_;
    double                 largest_stretch_ = 1;
    dealii::Vector<double> vertex_force_;
    double                 smallest_gap_ = 0, largest_penetration_ = 0;
    /// smallest_gap_ by the pairs' side: [0] self contact, [o + 1]
    /// obstacle o.
    std::vector<double> smallest_gap_by_side_;
    mutable Timing      timing_;
    bool                pending_ = false;
    /// Project the pair Hessians: after a failed attempt (restore(), on
    /// retry) or a climbing correction (on stall), until the next save().
    bool                                       projecting_this_step_ = false;
    bool                                       exact_tangent_        = false;
    std::vector<std::vector<dealii::Point<3>>> trial_current_;
    bool                                       trial_pending_ = false;
    /// What prepare() found at the last trial evaluation (line search).
    /// Its pairs and obstacle advance depend on nothing but the shell's
    /// positions, the target time and the obstacles' positions before the
    /// advance; when Newton then moves the shell to exactly the trial's
    /// shape (the accepted trial), prepare() takes them from here instead
    /// of searching again.
    struct Detection
    {
      std::vector<dealii::Point<3>>              positions;
      double                                     target_time = 0;
      std::vector<std::vector<dealii::Point<3>>> obstacles_before;
      std::vector<std::vector<dealii::Point<3>>> obstacles_after;
      std::vector<std::optional<Tree>> trees_after; ///< of those that moved
      bool                             pending = false;
      std::vector<Pair>                pairs;
    };
    std::optional<Detection> trial_detection_;
    /// Takes the trial's detection if its inputs are the present ones.
    bool reuse_trial_detection();

    /// Half the thickness of the pair's shell vertex, triangle or edge
    /// plus the obstacle's offset: the distance the pair must keep.
    double automatic_barrier_stiffness(double stiffness_per_area,
                                       double load_pressure) const;
    double offset(const Pair &pair) const;
    /// The current thickness of shell vertex v and of shell triangle t:
    /// the reference's times the stretch (of the triangle's vertices, on
    /// average) with Element/Thickness stretch (contact_thickness.cc).
    double vertex_thickness(unsigned int v) const;
    double triangle_thickness(unsigned int t) const;
    /// largest_thickness_ times the largest stretch: for the reach.
    double largest_current_thickness() const;
    /// Reads the stretches of 'state' (nothing without them).
    void update_stretches(const model::ShellState &state);
    /// How much any pair's offset (both sides' halves) has grown since the
    /// stretches were 'before': the largest thickening times the largest
    /// reference thickness (length; 0 without stretches).
    double offset_growth_since(const std::vector<double> &before) const;
    /// The pair's shell vertices in pair_dofs() order, with d offset /
    /// d stretch of each; returns how many.
    unsigned int offset_slopes(const Pair                  &pair,
                               std::array<unsigned int, 4> &vertices,
                               std::array<double, 4>       &slopes) const;
    /// The pair's energy w m phi(g) through g = distance - offset(stretch):
    /// the block of its stretches' force and their coupling to the
    /// translations of 'translations' (pair_dofs()).
    void add_stretch_terms(const Pair                    &pair,
                           const std::array<Point<3>, 4> &points,
                           const SquaredDistance         &s,
                           double                         weight,
                           const ScalarDerivatives       &phi,
                           const PairEnergy              &energy,
                           const model::DofBlock         &translations,
                           const model::BlockSink        &sink,
                           bool                           with_tangent) const;
    /// The stretch block's tangent: the stretches' coupling to the pair's
    /// shell translations and to each other ('curvature' = w m phi'').
    static void stretch_tangent(const std::vector<double>  &slopes,
                                const Coordinates12        &slope_of_force,
                                ShellCoordinates            shell,
                                double                      curvature,
                                dealii::FullMatrix<double> &matrix);
    /// The largest fraction of 'correction' whose thickening grows each
    /// pair's offset by at most 0.09 of its gap (the step filter keeps a
    /// tenth against the motion), and an out-of-reach pair's by 0.09 of
    /// the activation distance: so every gap stays open.
    double thickening_fraction(const dealii::Vector<double> &correction) const;
    /// Whether the pair's searched distance puts it beyond the reach of
    /// its own offset, where its energy is zero.
    bool beyond_reach(const Pair &pair) const;
    /// The same for shell edge e (the mean of its vertices' offsets).
    double edge_offset(unsigned int obstacle, unsigned int e) const;
    /// Obstacle o's work since the last save().
    double step_work(unsigned int o) const;
    /// Adds a pair's force block to the vertex force field and to its
    /// obstacle's force on the shell.
    void add_shell_force(const Pair &pair, const model::DofBlock &block);
    /// Lists the shell's and the obstacles' edges (constructor).
    void build_edges();
    /// Forgets the gaps and penetration seen since the last save().
    void forget_gaps();
    class PairSelector;
    /// Adds the edge-edge pair (two edges, points p and mesh vertex ids)
    /// to the selector if its distance is below 'reach'; returns the
    /// distance.
    double offer_edge_pair(PairSelector                  &selector,
                           Pair                           pair,
                           const std::array<Point<3>, 4> &p,
                           const std::array<unsigned, 4> &ids,
                           double                         reach) const;
    /// Candidate pairs, in rows: per query primitive (a shell vertex, an
    /// obstacle vertex or a shell edge), the primitives of the other side
    /// ('other') whose boxes came within its reach plus the lists' margin,
    /// and their distance then ('distance'; -inf in lists made for one
    /// swept motion, which carry none).
    struct CandidateRows
    {
      std::vector<unsigned int> start{0}, other;
      std::vector<double>       distance;
      /// Per row: the smallest listed distance (infinite for an empty row)
      /// and the largest offset a pair of the row keeps (length). A row
      /// a screen clears with both has each of its pairs cleared, to the
      /// bit (the screens' tests are monotone in each), so the step filter
      /// and the pair search skip it without reading its pairs.
      std::vector<double> nearest, thickest;
      /// Per pair: the distance the pair search last found, plus the
      /// search clock's reading then (Screen::clock; length). -inf until
      /// searched. Written by the search alone.
      std::vector<double> anchored;
      /// The largest offset kept so far in the row end_row() closes next.
      double thickest_of_open_row = 0;
      void   clear();
      /// Appends a pair with the primitive on the row's other side, its
      /// listed distance and the offset it keeps (kept, length).
      void add(unsigned int primitive, double listed, double kept);
      /// Closes the current row, sorted by primitive: the order of the
      /// pairs, hence the round-off of every sum over them, then depends
      /// on nothing but the pairs (not on the R-tree, not on when the
      /// lists were made), so a restarted run repeats the uninterrupted one.
      void end_row();
    };
    /// The rows of every kind of pair: per obstacle, shell vertices (in
    /// the order of shell_vertices_) against its triangles, its vertices
    /// against shell triangles and shell edges against its edges; shell
    /// vertices against shell triangles and shell edges e against shell
    /// edges f > e. With the positions they were made at and their
    /// margin (length; < 0: none made yet). See contact_candidates.cc.
    struct Candidates
    {
      std::vector<dealii::Point<3>>              shell;
      std::vector<std::vector<dealii::Point<3>>> obstacles;
      /// The shell's thickness stretches when the lists were made (empty
      /// without Element/Thickness stretch).
      std::vector<double>        stretches;
      double                     margin = -1;
      std::vector<CandidateRows> vertex_triangle, triangle_vertex, edge_edge;
      CandidateRows              self_vertex_triangle, self_edge_edge;
      /// Where the last pair search found the shell and the obstacles,
      /// and the longest move of any of their vertices from one search to
      /// the next, summed since the lists were made (length); for self
      /// contact twice the longest move less a common translation.
      std::vector<dealii::Point<3>>              searched_shell;
      std::vector<std::vector<dealii::Point<3>>> searched_obstacles;
      /// obstacle_stamp() of 'obstacles' and of 'searched_obstacles'.
      std::vector<std::uint64_t> obstacle_stamps, searched_stamps;
      double                     shell_travel = 0, self_travel = 0;
      std::vector<double>        obstacle_travel;
    };
    /// What a listed pair's distance tells without computing it: the
    /// pair is now at most 'shift' nearer than when listed.
    struct Screen
    {
      double shift = 0;
      /// The search clock of these pairs: their two sides' travels added
      /// (Candidates; length). A pair is now at most clock - (the clock
      /// when it was last searched) nearer than then.
      double clock = 0;
      /// The longest move of any point of the filter's motion (length).
      double largest_move = std::numeric_limits<double>::infinity();
      /// True if the pair is out of 'reach' (no pair of the search).
      bool skips_search(double listed, double reach) const;
      /// The same, by the distance the search last found (anchored).
      bool skips_anchored(double anchored, double reach) const;
      /// True if skips_filter() is, whatever the pair's moves, by
      /// 'largest_move': decided before the pair's points are gathered.
      bool clears(double listed, double offset) const;
      /// True if additive_ccd() would let the whole motion of the pair's
      /// points ('moves') pass.
      bool skips_filter(double               listed,
                        double               offset,
                        const Displacements &moves) const;
    };
    /// The shell moving from x by dx and obstacle 'moving' by dX (null,
    /// and invalid_obstacle: that side keeps still).
    struct Motion
    {
      const std::vector<dealii::Point<3>>     &x;
      const std::vector<dealii::Tensor<1, 3>> *dx;
      unsigned int                             moving;
      const std::vector<dealii::Tensor<1, 3>> *dX;
    };
    static constexpr unsigned int invalid_obstacle = -1;
    Candidates                    candidates_;
    /// How far beyond its reach a pair is listed (length): the shell and
    /// an obstacle may together drift this far (the shell half of it with
    /// self contact) before the lists are made anew.
    double candidate_margin() const;
    bool   covers(const Motion        &motion,
                  std::vector<Screen> &obstacle_screens,
                  Screen              &self_screen) const;
    void   update_candidates(const std::vector<dealii::Point<3>> &x,
                             std::vector<Screen> &obstacle_screens,
                             Screen              &self_screen);
    void   make_obstacle_candidates(unsigned int  o,
                                    const Motion &motion,
                                    const Tree   &shell_tree,
                                    double        margin,
                                    bool          measure,
                                    Candidates   &c) const;
    void   make_edge_candidates(unsigned int  o,
                                const Motion &motion,
                                const Tree   &obstacle_tree,
                                double        margin,
                                bool          measure,
                                Candidates   &c) const;
    void   make_self_candidates(const Motion &motion,
                                const Tree   &shell_tree,
                                double        margin,
                                bool          measure,
                                Candidates   &c) const;
    /// The step filter: the largest fraction of the motion that keeps
    /// every pair (of obstacle 'only', or of all and self contact) apart.
    double filter_fraction(const Motion &motion, unsigned int only) const;
    /// Whether every pair of the row is out of the pair search's reach
    /// (pair_reach of the pair's offset; the reach is monotone in it).
    bool out_of_reach(const Screen        &screen,
                      const CandidateRows &rows,
                      unsigned int         row) const;
    /// Whether the screen clears every pair of the row (CandidateRows::
    /// nearest and thickest) at the filter's offsets.
    bool   clears_row(const Screen        &screen,
                      const CandidateRows &rows,
                      unsigned int         row) const;
    double pair_filter_fraction(const Screen        &screen,
                                double               listed,
                                PrimitivePair        type,
                                const Points4       &points,
                                const Displacements &moves,
                                double               offset) const;
    double obstacle_filter_fraction(const Motion     &motion,
                                    unsigned int      o,
                                    const Candidates &c,
                                    const Screen     &screen) const;
    double edge_filter_fraction(const Motion     &motion,
                                unsigned int      o,
                                const Candidates &c,
                                const Screen     &screen) const;
    double self_filter_fraction(const Motion     &motion,
                                const Candidates &c,
                                const Screen     &screen) const;
    /// Boxes of obstacle o's triangles, swept by dX if given.
    Tree
    obstacle_triangle_tree(unsigned int                             o,
                           const std::vector<dealii::Tensor<1, 3>> *dX) const;
    /// Shell edges against the edges of obstacle o's triangles within
    /// reach (one pair per two edges).
    void find_edge_pairs(unsigned int                         o,
                         const std::vector<dealii::Point<3>> &x,
                         const Screen                        &screen,
                         PairSelector                        &selector);
    /// Which edges a query of edges_near() has found already: the
    /// number of the query that last found each edge.
    struct EdgeMarks
    {
      explicit EdgeMarks(std::size_t n_edges) : last(n_edges, 0) {}
      std::vector<unsigned int> last;
      unsigned int              query = 0;
    };
    /// The edges (by 'triangle_edges', the obstacle's or the shell's) of
    /// the triangles in 'tree' whose boxes meet the box of 'corners'
    /// inflated by 'inflation' (each once, in the order found; 'marks' has
    /// one entry per edge of 'triangle_edges').
    static void
    edges_near(const Tree                                 &tree,
               const std::vector<std::array<unsigned, 3>> &triangle_edges,
               EdgeMarks                                  &marks,
               std::initializer_list<dealii::Point<3>>     corners,
               double                                      inflation,
               std::vector<unsigned int>                  &edges);
    /// Self contact of edges e and f: the mean of their half thicknesses.
    double self_edge_offset(unsigned int e, unsigned int f) const;
    /// Edge pairs of the same connected piece nearer than the exclusion
    /// distance in the reference configuration (after the vertex ones).
    void exclude_reference_edge_neighbours(
        const std::vector<unsigned int> &piece_of_vertex);
    void find_self_edge_pairs(const std::vector<dealii::Point<3>> &x,
                              const Screen                        &screen,
                              PairSelector                        &selector);
    /// weight * m * phi and its derivatives for a pair at 'points' (the
    /// Hessian only 'with_hessian': a residual needs the gradient alone).
    PairEnergy pair_energy(const Pair                    &pair,
                           const std::array<Point<3>, 4> &points,
                           const SquaredDistance         &s,
                           double                         weight,
                           const ScalarDerivatives       &phi,
                           bool                           with_hessian) const;
    double     offset(unsigned int obstacle,
                      bool         shell_vertex_side,
                      unsigned int shell) const;
    /// The largest offset of any pair of this obstacle.
    double largest_offset(unsigned int obstacle) const;
    /// Self contact: the distance shell vertex v and shell triangle t
    /// keep (the mean of their half thicknesses, i.e. the sum of halves).
    double self_offset(unsigned int v, unsigned int t) const;
    /// The largest self-contact offset of vertex v (of edge e) with any
    /// triangle (edge), plus 'activation': how far its search reaches.
    double self_reach(unsigned int v, double activation) const;
    double self_edge_reach(unsigned int e, double activation) const;
    /// Finds, once, the triangles each shell vertex must not pair with
    /// beyond its own: those of its connected piece that were nearer
    /// than the exclusion distance in the reference configuration.
    void exclude_reference_neighbours();
    /// The positions the pair's other side takes its points from, now and
    /// at the last converged state.
    const std::vector<dealii::Point<3>> &other_side(const Pair &pair) const;
    const std::vector<dealii::Point<3>> &
    saved_other_side(const Pair &pair) const;
    /// The shell vertex a pair's gap is charged to (diagnostics).
    unsigned int pair_shell_vertex(const Pair &pair) const;
    /// Per shell vertex, its smallest gap to each obstacle in the pairs of
    /// the last evaluation (diagnostics).
    std::map<unsigned int, std::map<unsigned int, double>>
    obstacle_gaps_by_vertex() const;
    /// Per shell vertex, the sorted triangles it does not pair with: its
    /// own (v is their corner) and those of its connected piece that were
    /// nearer than Self contact exclusion times their offset in the
    /// reference configuration.
    std::vector<std::vector<unsigned int>> excluded_;
    unsigned int                           self_active_pairs_ = 0;
    double                                 reach(unsigned int obstacle) const;
    /// The distance within which a pair that must keep 'offset' has a
    /// force: offset plus the barrier's activation distance (the offset
    /// alone for the penalty). A pair is looked for within its own reach,
    /// not the obstacle's largest: the thin rim of a lens searches a
    /// smaller box than its thick centre.
    double pair_reach(double offset) const;
    /// The box of 'points', inflated, made without the heap.
    static dealii::BoundingBox<3>
    box_of(std::initializer_list<dealii::Point<3>> points, double inflation);
    /// The box of the shell's vertices at x and x + dx, inflated by
    /// max_reach() (meets every query box that meets a shell triangle).
    dealii::BoundingBox<3>
    swept_shell_box(const std::vector<dealii::Point<3>>     &x,
                    const std::vector<dealii::Tensor<1, 3>> *dx) const;
    std::vector<dealii::Point<3>>
    shell_positions(const model::ShellState &state) const;
    /// Obstacle o's positions (current_[o]) changed: marks its tree for a
    /// rebuild where it is now and counts the change (obstacle_moves_).
    void obstacle_moved(unsigned int obstacle);
    /// obstacle_moves_[o] if obstacle o's positions are all finite, else
    /// 0 (no count): a stamp the lists keep of the positions they saw.
    std::uint64_t obstacle_stamp(unsigned int o) const;
    /// Obstacle o's tree where it is now (built if marked).
    const Tree &obstacle_tree(unsigned int o) const;
    double      max_reach() const;
    /// Boxes of the shell triangles (swept by dx if given), inflated. The
    /// pair searches use them uninflated and inflate their query boxes
    /// by what each query point must reach: a thin rim or haptic does not
    /// search as far as the thick optic.
    Tree shell_triangle_tree(const std::vector<dealii::Point<3>>     &x,
                             const std::vector<dealii::Tensor<1, 3>> *dx,
                             double inflation) const;
    /// The four points of a pair (its point first) from the shell's and
    /// the obstacle's vertex positions.
    std::array<dealii::Point<3>, 4>
    pair_points(const Pair                          &pair,
                const std::vector<dealii::Point<3>> &shell,
                const std::vector<dealii::Point<3>> &obstacle) const;
    /// Friction of the pairs in contact at the last converged state.
    void   add_friction_terms(const model::BlockSink &sink, bool with_tangent);
    double friction_coefficient(const Pair &pair) const;
    /// eps of friction this step: Stiction velocity times the step, at
    /// least Stiction displacement (length).
    double smoothing_length() const;
    /// Returns where the obstacle's share of the force acts (0 for a
    /// self-contact pair or no force).
    dealii::Tensor<1, 3> add_friction(const NormalForce &lagged,
                                      bool               with_tangent,
                                      model::DofBlock   &block);
    /// Blocks reused across the pairs of an evaluation, one per number of
    /// the pair's shell vertices (1 to 4): one block sized to each pair in
    /// turn would be allocated anew whenever the kind of pair changes,
    /// nearly once a pair.
    using PairBlocks = std::array<model::DofBlock, 5>;
    /// The block of 'blocks' for the pair, holding the pair's shell DoFs.
    model::DofBlock &pair_dofs(const Pair &pair, PairBlocks &blocks) const;
    /// force_slopes_: emptied before a tangent's pairs, then each block of
    /// a followed obstacle's pair (contact_input.cc).
    void reset_force_slopes();
    bool follows_force(const Pair &pair) const;
    /// A friction pair: 'shell_block', its exact Hessian on the
    /// translations 'dofs' of its shell points, and 'application', where
    /// the obstacle's share of the friction force acts.
    void
    add_force_slopes(const Pair                                         &pair,
                     const std::vector<dealii::types::global_dof_index> &dofs,
                     const dealii::FullMatrix<double> &shell_block,
                     const dealii::Tensor<1, 3>       &application);
    /// A contact pair, from its energy's Hessian and its points.
    void
         add_force_slopes(const Pair                                         &pair,
                          const std::vector<dealii::types::global_dof_index> &dofs,
                          const PairEnergy                                   &energy,
                          const std::array<dealii::Point<3>, 4> &points);
    void pair_hessian(const PairEnergy           &energy,
                      ShellCoordinates            shell,
                      dealii::FullMatrix<double> &matrix) const;
    /// The rest of the move of the pair's obstacle points (zero at its
    /// shell points), from where the step filter held them to the target.
    std::array<dealii::Tensor<1, 3>, 4>
         remaining_obstacle_moves(const Pair &pair) const;
    void anticipate_obstacle(const Pair       &pair,
                             const PairEnergy &energy,
                             model::DofBlock  &block) const;
    void record_pair(const Pair                            &pair,
                     const std::array<dealii::Point<3>, 4> &points,
                     const Coordinates12                   &gradient,
                     double                                 gap,
                     const model::DofBlock                 &block);
    void reset_pair_records();
    /// The pairs within reach at x, from the candidate lists (made anew
    /// if they no longer cover x).
    void find_pairs(const std::vector<dealii::Point<3>> &x);
    /// Adds the moves since the last search to the lists' travels and
    /// sets the screens' clocks from them.
    void advance_search_clock(const std::vector<dealii::Point<3>> &x,
                              std::vector<Screen> &obstacle_screens,
                              Screen              &self_screen);
    void find_shell_vertex_pairs(unsigned int                         obstacle,
                                 const std::vector<dealii::Point<3>> &x,
                                 const Screen                        &screen,
                                 PairSelector                        &selector);
    void find_self_pairs(const std::vector<dealii::Point<3>> &x,
                         const Screen                        &screen,
                         PairSelector                        &selector);
    void find_obstacle_vertex_pairs(unsigned int obstacle,
                                    const std::vector<dealii::Point<3>> &x,
                                    const Screen                        &screen,
                                    PairSelector &selector);
    void advance_obstacles(const std::vector<dealii::Point<3>> &x);
    void set_target_time(double time);
  };

  /// Weights w of a pair's four points such that sum_k w_k x_k is the
  /// vector between its two closest points (from the second primitive's
  /// to the first's), given their parameters (SquaredDistance::parameters):
  /// {1, -(1 - b - c), -b, -c} for a point and a triangle, {1 - s, s,
  /// -(1 - t), -t} for two segments.
  std::array<double, 4>
  closest_point_weights(bool                         edge_edge,
                        const std::array<double, 2> &parameters);
  /// sum_k w_k x_k: the vector between the closest points.
  dealii::Tensor<1, 3>
  closest_point_difference(bool                                   edge_edge,
                           const std::array<dealii::Point<3>, 4> &points,
                           const std::array<double, 2>           &parameters);

  /// The Contribution that adds a Contact to a ShellProblem.
  class ContactContribution : public model::Contribution
  {
  public:
    explicit ContactContribution(Contact &contact);
    std::string      name() const override;
    model::ForceKind kind() const override;
    bool             has_cell_terms() const override;
    void             add_blocks(const model::EvaluationPoint &point,
                                const model::BlockSink       &sink,
                                bool                          with_tangent) override;
    void             prepare(const model::EvaluationPoint &point) override;
    std::uint64_t
    update_coupled_vertices(const model::EvaluationPoint &point) const override;
    void coupled_vertices(
        std::vector<std::array<unsigned int, 2>> &pairs) const override;
    bool   couples_beyond_cells() const override;
    bool   pending() const override;
    double admissible_fraction(
        const model::ShellState      &state,
        const dealii::Vector<double> &correction) const override;
    void extrapolate_reports(const dealii::Vector<double> &correction) override;
    void save() override;
    void restore() override;
    void begin_trial() override;
    void end_trial() override;
    bool symmetric_tangent() const override;
    /// The pairs' barrier or penalty energy plus friction's lagged
    /// potential (its dissipation over the step), at the last evaluation.
    /// While an obstacle is held back by the step filter, the residual
    /// also holds its anticipated move, which no potential has.
    bool   has_potential() const override;
    double global_energy(const model::EvaluationPoint &point) const override;
    bool   use_convex_tangent() override;
    std::string failure_context() const override;

  private:
    Contact &contact_;
  };
} // namespace coshell::contact
