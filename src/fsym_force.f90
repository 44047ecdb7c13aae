!> The force model a user supplies, and the recorder of force-evaluation points.
!>
!> State convention: positions `q(d,n)` and velocities `v(d,n)`, d dimensions, n particles.
!> A model returns accelerations `a(q)` (required), and optionally the gradient term
!> g_j = (1/m_j) d/dq_j sum_i m_i |a_i|^2 (for unit masses the paper's grad |F|^2) and the
!> potential energy, and the flow of the other part of H (free flight unless overridden: a
!> planetary model's Kepler flow). A model supplies forces and flows; it never steps. User data
!> travels by extending `force_model_t`.
module fsym_force
    use fsym_kinds, only: wp, ik
    implicit none
    private

    integer, parameter, public :: EVAL_FORCE = 1         !! a force evaluation at the state
    integer, parameter, public :: EVAL_GRADIENT = 2      !! a gradient-term evaluation
    integer, parameter, public :: EVAL_EXTRAPOLATED = 3  !! a force at the extrapolated point

    !> A force model: accelerations, and optionally the gradient term and the potential.
    type, abstract, public :: force_model_t
    contains
        procedure(acceleration_iface), deferred :: acceleration  !! accelerations a(q) (required)
        procedure :: gradient => force_no_gradient      !! gradient term g(q) (optional)
        procedure :: has_gradient => force_has_no_gradient  !! whether `gradient` is provided
        procedure :: potential => force_no_potential    !! potential energy (optional)
        procedure :: has_potential => force_has_no_potential  !! whether `potential` is provided
        procedure :: drift => force_free_drift
            !! the flow of the other part of H over dt (default: free flight q <- q + dt v)
        procedure :: has_drift => force_has_free_drift
            !! whether `drift` is overridden (the kernel does free flight itself otherwise)
        procedure :: set_time => force_ignore_time
            !! told the time of the stage before each evaluation (a time-dependent force)
        procedure :: has_time => force_has_no_time
            !! whether `set_time` is overridden (default: no, the force does not depend on t)
        procedure :: local_frequency => force_no_frequency
            !! largest local frequency squared, for the step-size guard (optional)
        procedure :: has_frequency => force_has_no_frequency
            !! whether `local_frequency` is provided
        procedure :: failure => force_failure
            !! the library status and text of the model's last failure (default: unchanged)
    end type force_model_t

    !> Interface of `force_model_t%acceleration`.
    abstract interface
        subroutine acceleration_iface(self, q, a, stat)
            !! Accelerations a(:,j) of every particle j at positions q. Set `stat` non-zero to
            !! report a failure (it enters as zero); the step is then undone.
            import :: force_model_t, wp
            implicit none
            class(force_model_t), intent(inout) :: self  !! the model (may keep counters)
            real(wp), intent(in), contiguous :: q(:, :)               !! positions (d, n)
            real(wp), intent(out), contiguous :: a(:, :)              !! accelerations (d, n)
            integer, intent(inout) :: stat                !! 0 on entry; non-zero = failure
        end subroutine acceleration_iface
    end interface

    !> Receives every force-evaluation position while a stepper runs (optional argument of
    !> `step`/`run`); it must not allocate if it is to keep the step allocation-free.
    type, abstract, public :: recorder_t
    contains
        procedure(record_iface), deferred :: record     !! receive one evaluation point
    end type recorder_t

    !> Interface of `recorder_t%record`.
    abstract interface
        subroutine record_iface(self, step, stage, kind, q)
            !! One evaluation: step number, stage of the scheme, kind (`EVAL_*`), position.
            import :: recorder_t, wp, ik
            implicit none
            class(recorder_t), intent(inout) :: self  !! the recorder
            integer(ik), intent(in) :: step           !! step number (1 = first step taken)
            integer, intent(in) :: stage              !! stage index within the scheme
            integer, intent(in) :: kind               !! `EVAL_FORCE`, `EVAL_GRADIENT`, ...
            real(wp), intent(in) :: q(:, :)           !! where the evaluation happened
        end subroutine record_iface
    end interface

contains

    !> Default gradient term: not provided (sets `stat` = 1). Override it together with
    !> `has_gradient`.
    subroutine force_no_gradient(self, q, a, g, stat)
        class(force_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)               !! positions (d, n)
        real(wp), intent(in), contiguous :: a(:, :)   !! accelerations at q, already computed
        real(wp), intent(out), contiguous :: g(:, :)              !! gradient term (d, n)
        integer, intent(inout) :: stat                !! 0 on entry; non-zero = failure
        g = 0.0_wp
        stat = 1
        associate (unused_self => self, unused_q => q, unused_a => a); end associate
    end subroutine force_no_gradient

    !> Whether `gradient` is provided (default: no).
    logical function force_has_no_gradient(self)
        class(force_model_t), intent(in) :: self  !! the model
        force_has_no_gradient = .false.
        associate (unused => self); end associate   ! the interface's arguments
    end function force_has_no_gradient

    !> Default potential: not provided (returns 0 and sets `stat` = 1).
    subroutine force_no_potential(self, q, epot, stat)
        class(force_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)               !! positions (d, n)
        real(wp), intent(out) :: epot                 !! total potential energy
        integer, intent(inout) :: stat                !! 0 on entry; non-zero = failure
        epot = 0.0_wp
        stat = 1
        associate (unused_self => self, unused_q => q); end associate   ! the interface's arguments
    end subroutine force_no_potential

    !> Default drift: free flight, q <- q + dt v (the kinetic part p^2/2 of H). A model whose
    !> splitting has another solvable part (a Kepler flow for planetary systems, the
    !> Wisdom-Holman splitting) overrides it, together with `has_drift`; the kernel then calls
    !> it at every drift stage with dt = c h, and restores q and v itself when it sets `stat`.
    !> A drift never steps: it applies one exact flow and knows nothing of the scheme.
    subroutine force_free_drift(self, q, v, dt, stat)
        class(force_model_t), intent(inout) :: self      !! the model
        real(wp), intent(inout), contiguous :: q(:, :)   !! positions (d, n)
        real(wp), intent(inout), contiguous :: v(:, :)   !! velocities (d, n)
        real(wp), intent(in) :: dt                       !! time to flow (any sign)
        integer, intent(inout) :: stat                   !! 0 on entry; non-zero = failure
        q = q + dt * v
        associate (unused_self => self, unused => stat); end associate   ! the interface's arguments
    end subroutine force_free_drift

    !> Whether `drift` is overridden (default: no, the kernel does free flight inline).
    logical function force_has_free_drift(self)
        class(force_model_t), intent(in) :: self  !! the model
        force_has_free_drift = .false.
        associate (unused => self); end associate   ! the interface's arguments
    end function force_has_free_drift

    !> Default `set_time`: the force does not depend on time. A model whose force does (a
    !> driven oscillator, a rotating potential) overrides it and `has_time`: before every
    !> evaluation of a kick stage the kernel calls `set_time(t)` with the stage's time
    !> (the step's start plus the drift weights before the stage, times h), and the model
    !> keeps t for its `acceleration` and `gradient`. Existing models need no change.
    subroutine force_ignore_time(self, t)
        class(force_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in) :: t                     !! time of the next evaluation
        associate (unused_self => self, unused => t); end associate   ! the interface's arguments
    end subroutine force_ignore_time

    !> Whether `set_time` is overridden (default: no).
    logical function force_has_no_time(self)
        class(force_model_t), intent(in) :: self  !! the model
        force_has_no_time = .false.
        associate (unused => self); end associate   ! the interface's arguments
    end function force_has_no_time

    !> Whether `potential` is provided (default: no).
    logical function force_has_no_potential(self)
        class(force_model_t), intent(in) :: self  !! the model
        force_has_no_potential = .false.
        associate (unused => self); end associate   ! the interface's arguments
    end function force_has_no_potential

    !> Default local frequency: not provided (omega2 = 0, r = 0, `stat` = 1). A model that
    !> overrides it (with `has_frequency`) returns the largest omega^2 of its bodies or pairs
    !> at q, e.g. 2 mu / r^3 for a Kepler pair at distance r, and that r; the integrator's
    !> step-size guard refuses steps with h omega above the method's stability limit.
    subroutine force_no_frequency(self, q, omega2, r, stat)
        class(force_model_t), intent(inout) :: self      !! the model
        real(wp), intent(in), contiguous :: q(:, :)      !! positions (d, n)
        real(wp), intent(out) :: omega2                  !! largest local omega^2
        real(wp), intent(out) :: r                       !! distance where it occurs
        integer, intent(inout) :: stat                   !! 0 on entry; non-zero = failure
        omega2 = 0.0_wp; r = 0.0_wp
        stat = 1
        associate (unused_self => self, unused_q => q); end associate   ! the interface's arguments
    end subroutine force_no_frequency

    !> Whether `local_frequency` is provided (default: no).
    logical function force_has_no_frequency(self)
        class(force_model_t), intent(in) :: self  !! the model
        force_has_no_frequency = .false.
        associate (unused => self); end associate   ! the interface's arguments
    end function force_has_no_frequency

    !> Default `failure`: nothing to add. Called by the faces right after a step failed with
    !> FSYM_ERR_MODEL (a non-zero `stat` from this model), so that a model whose failures
    !> have a meaning of their own can say which: it may replace `code` by a library status
    !> (a planetary model's close encounter: FSYM_ERR_ENCOUNTER) and put its text into `msg`.
    subroutine force_failure(self, code, msg)
        class(force_model_t), intent(in) :: self     !! the model
        integer, intent(inout) :: code               !! FSYM_ERR_MODEL on entry
        character(len=*), intent(inout) :: msg       !! blank on entry; the model's text
        associate (unused_self => self, unused_code => code, unused_msg => msg); end associate
    end subroutine force_failure

end module fsym_force
