!> What every time stepper of the library shares: the interface of `step` and `run`, the
!> clock (time as t0 + k h, never a running sum), and the evaluation counters. The splitting
!> integrator and the Runge-Kutta-Nystrom comparator extend it.
module fsym_stepper
    use fsym_kinds, only: wp, ik, fsym_same
    use fsym_status
    use fsym_force, only: force_model_t, recorder_t
    implicit none
    private

    public :: stepper_run

    !> Receives the state every `every` steps of a `run` (optional argument); it may stop
    !> the run. User data travels by extending this type. Override `observe` (the state), or
    !> `observe_model` to be given the run's force model too (e.g. for the energy); the
    !> steppers call `observe_model`, whose default calls `observe`.
    type, abstract, public :: observer_t
    contains
        procedure :: observe => observer_ignore   !! look at the state; may stop the run
        procedure :: observe_model => observer_pass
            !! look at the state and the model; may stop the run (default: `observe`)
    end type observer_t

    !> A time stepper for q' = v, v' = a(q) on arrays q(d,n), v(d,n).
    type, abstract, public :: stepper_t
        private
        character(len=:), allocatable :: label
        integer :: d = 0, n = 0
        logical :: splitting = .false., forward = .false., symplectic = .false.
        integer :: nf_step = 0, ng_step = 0
        integer(ik) :: nsteps = 0, nforce = 0, ngrad = 0
        integer(ik) :: k_since = 0           ! steps since the step size last changed
        real(wp) :: t_base = 0.0_wp          ! time when the step size last changed
        real(wp) :: h_now = 0.0_wp           ! current step size
        logical :: stopped = .false.         ! the last run was stopped by its observer
    contains
        procedure(step_iface), deferred :: step         !! advance (q, v) by one step h
        procedure :: run_steps => stepper_run           !! `run` with an int64 count
        procedure, non_overridable :: run_steps_int => stepper_run_int
            !! `run` with a default-integer count
        generic :: run => run_steps, run_steps_int      !! take nsteps steps
        procedure, non_overridable :: run_to => stepper_run_to
            !! steps of h up to a final time, the last one shortened to land on it
        procedure :: time => stepper_time               !! current time
        procedure :: set_time => stepper_set_time       !! set the clock
        procedure :: steps => stepper_steps             !! steps completed since init
        procedure :: force_evaluations => stepper_force_evaluations  !! force evaluations since init
        procedure :: gradient_evaluations => stepper_gradient_evaluations
            !! gradient evaluations since init
        procedure :: name => stepper_name               !! method label
        procedure :: is_splitting => stepper_is_splitting  !! true for splitting methods
        procedure :: is_forward => stepper_is_forward   !! true for forward methods
        procedure :: is_symplectic => stepper_is_symplectic  !! true when symplectic for every force
        procedure :: forces_per_step => stepper_forces_per_step  !! force evaluations per step
        procedure :: gradients_per_step => stepper_gradients_per_step
            !! gradient evaluations per step
        procedure :: dims => stepper_dims               !! dimensions and particles
        procedure :: describe_stepper                   !! for extensions: set description and shape
        procedure :: count_step                         !! for extensions: one step completed
        procedure :: counters
            !! for extensions: read or store the counters
        procedure, non_overridable :: account
            !! for extensions: store the counters and count steps (one call per kernel call)
        procedure :: note_stop
            !! for extensions: whether the observer stopped the run
        procedure :: clock_state
            !! for extensions (checkpoints): read or set the clock and the step count
    end type stepper_t

    !> Interface of `stepper_t%step`.
    abstract interface
        subroutine step_iface(self, model, q, v, h, stat, errmsg, recorder)
            !! Advance (q, v) by one step h. On failure `stat` is non-zero, `errmsg` says why, and
            !! q and v are exactly as they were on entry; the stepper stays usable.
            import :: stepper_t, force_model_t, recorder_t, wp
            implicit none
            class(stepper_t), intent(inout) :: self               !! the stepper
            class(force_model_t), intent(inout) :: model          !! force model
            real(wp), intent(inout), contiguous :: q(:, :)        !! positions (d, n)
            real(wp), intent(inout), contiguous :: v(:, :)        !! velocities (d, n)
            real(wp), intent(in) :: h                             !! step (may be negative)
            integer, intent(out), optional :: stat                !! status code
            character(len=*), intent(inout), optional :: errmsg   !! message on error
            class(recorder_t), intent(inout), optional :: recorder  !! force-point recorder
        end subroutine step_iface
    end interface

contains

    !> Default `observe`: looks at nothing (override it, or `observe_model`). Called after step
    !> number `step` (counted since `init`) at time t; set `stop` to .true. to end the run
    !> there (it then returns success).
    subroutine observer_ignore(self, q, v, t, step, stop)
        class(observer_t), intent(inout) :: self          !! the observer
        real(wp), intent(in), contiguous :: q(:, :)       !! positions (d, n)
        real(wp), intent(in), contiguous :: v(:, :)       !! velocities (d, n)
        real(wp), intent(in) :: t                         !! time
        integer(ik), intent(in) :: step                   !! steps completed since init
        logical, intent(inout) :: stop                    !! .false. on entry
        associate (u1 => self, u2 => q, u3 => v, u4 => t, u5 => step, u6 => stop); end associate
    end subroutine observer_ignore

    !> Default `observe_model`: calls `observe` (the model is not needed there). Override it
    !> to see the run's force model, e.g. `model%potential` for the energy.
    subroutine observer_pass(self, model, q, v, t, step, stop)
        class(observer_t), intent(inout) :: self          !! the observer
        class(force_model_t), intent(inout) :: model      !! the run's force model
        real(wp), intent(in), contiguous :: q(:, :)       !! positions (d, n)
        real(wp), intent(in), contiguous :: v(:, :)       !! velocities (d, n)
        real(wp), intent(in) :: t                         !! time
        integer(ik), intent(in) :: step                   !! steps completed since init
        logical, intent(inout) :: stop                    !! .false. on entry
        associate (unused => model); end associate   ! not needed by `observe`
        call self%observe(q, v, t, step, stop)
    end subroutine observer_pass

    !> Take `nsteps` steps of size h; stops at the first failing step, leaving the state of the
    !> last good step (check `stat`; `steps()` tells how far it got). With `observer`, its
    !> `observe` is called after every `every` (default 1) steps of this call; it may stop
    !> the run. The default `run`: one `step` after the other (public so that an extension
    !> overriding `run_steps` can fall back to it).
    subroutine stepper_run(self, model, q, v, h, nsteps, stat, errmsg, recorder, observer, every)
        class(stepper_t), intent(inout) :: self               !! the stepper
        class(force_model_t), intent(inout) :: model          !! force model
        real(wp), intent(inout), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(inout), contiguous :: v(:, :)        !! velocities (d, n)
        real(wp), intent(in) :: h                             !! step
        integer(ik), intent(in) :: nsteps                     !! number of steps
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        class(recorder_t), intent(inout), optional :: recorder  !! force-point recorder
        class(observer_t), intent(inout), optional :: observer  !! called every `every` steps
        integer, intent(in), optional :: every                !! observer interval (default 1)
        integer(ik) :: k, ke
        integer :: st
        logical :: stop
        character(len=512) :: msg
        st = FSYM_SUCCESS
        ke = 1
        if (present(every)) ke = max(1, every)
        self%stopped = .false.
        if (nsteps < 1) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'run: nsteps = '//fsym_int_text(nsteps)// &
                             ' (must be >= 1)', stat, errmsg)
            return
        end if
        do k = 1, nsteps
            call self%step(model, q, v, h, st, msg, recorder)
            if (st /= FSYM_SUCCESS) exit
            if (present(observer) .and. mod(k, ke) == 0) then
                stop = .false.
                call observer%observe_model(model, q, v, self%time(), self%nsteps, stop)
                self%stopped = stop
                if (stop) exit
            end if
        end do
        call fsym_pass(st, msg, stat, errmsg)
    end subroutine stepper_run

    !> `run` with `nsteps` a default integer.
    subroutine stepper_run_int(self, model, q, v, h, nsteps, stat, errmsg, recorder, observer, &
                               every)
        class(stepper_t), intent(inout) :: self               !! the stepper
        class(force_model_t), intent(inout) :: model          !! force model
        real(wp), intent(inout), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(inout), contiguous :: v(:, :)        !! velocities (d, n)
        real(wp), intent(in) :: h                             !! step
        integer, intent(in) :: nsteps                         !! number of steps
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        class(recorder_t), intent(inout), optional :: recorder  !! force-point recorder
        class(observer_t), intent(inout), optional :: observer  !! called every `every` steps
        integer, intent(in), optional :: every                !! observer interval (default 1)
        call self%run_steps(model, q, v, h, int(nsteps, ik), stat, errmsg, recorder, observer, &
                            every)
    end subroutine stepper_run_int

    !> Integrate from the current time to `t_end` with steps of h (its sign must point from
    !> `time()` to `t_end`): the whole steps that fit by `run`, then one shorter step that
    !> lands on t_end (none when the whole steps land within a relative 1e-12 of h). On
    !> success `time()` is exactly t_end. The observer, if any, sees the whole steps as in
    !> `run` and then the final state. A failure or an observer's stop ends it early.
    subroutine stepper_run_to(self, model, q, v, h, t_end, stat, errmsg, recorder, observer, &
                              every)
        class(stepper_t), intent(inout) :: self               !! the stepper
        class(force_model_t), intent(inout) :: model          !! force model
        real(wp), intent(inout), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(inout), contiguous :: v(:, :)        !! velocities (d, n)
        real(wp), intent(in) :: h                             !! step
        real(wp), intent(in) :: t_end                         !! final time
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        class(recorder_t), intent(inout), optional :: recorder  !! force-point recorder
        class(observer_t), intent(inout), optional :: observer  !! called every `every` steps
        integer, intent(in), optional :: every                !! observer interval (default 1)
        real(wp) :: span, rest, nwhole
        integer(ik) :: n, before
        integer :: st
        logical :: stop
        character(len=512) :: msg
        span = t_end - self%time()
        if (fsym_same(h, 0.0_wp) .or. .not. abs(h) <= huge(h) .or. &
            .not. abs(span) <= huge(span)) then
            call fsym_report(FSYM_ERR_BAD_STEP, 'run_to: h must be finite and non-zero, '// &
                             't_end finite', stat, errmsg)
            return
        end if
        if (.not. fsym_same(span, 0.0_wp) .and. (span > 0.0_wp .neqv. h > 0.0_wp)) then
            call fsym_report(FSYM_ERR_BAD_STEP, 'run_to: h points away from t_end', stat, &
                             errmsg)
            return
        end if
        nwhole = aint(span / h)
        if (nwhole > real(huge(n), wp)) then
            call fsym_report(FSYM_ERR_BAD_STEP, 'run_to: too many steps', stat, errmsg)
            return
        end if
        n = int(nwhole, ik)
        if (abs(span - real(n + 1, wp) * h) <= 1.0e-12_wp * abs(h)) n = n + 1
        before = self%nsteps
        st = FSYM_SUCCESS
        self%stopped = .false.
        if (n > 0) call self%run_steps(model, q, v, h, n, st, msg, recorder, observer, every)
        if (st /= FSYM_SUCCESS .or. self%stopped .or. self%nsteps - before < n) then
            call fsym_pass(st, msg, stat, errmsg); return      ! failed, or stopped
        end if
        rest = t_end - self%time()
        if (abs(rest) > 1.0e-12_wp * abs(h)) then
            call self%step(model, q, v, rest, st, msg, recorder)
            if (st /= FSYM_SUCCESS) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
            if (present(observer)) then
                stop = .false.
                call observer%observe_model(model, q, v, t_end, self%nsteps, stop)
            end if
        end if
        call self%set_time(t_end)
        self%h_now = h
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine stepper_run_to

    !> Current time t_base + k h.
    pure real(wp) function stepper_time(self)
        class(stepper_t), intent(in) :: self  !! the stepper
        stepper_time = self%t_base + real(self%k_since, wp) * self%h_now
    end function stepper_time

    !> Set the clock (e.g. to t0 before a run).
    pure subroutine stepper_set_time(self, t)
        class(stepper_t), intent(inout) :: self  !! the stepper
        real(wp), intent(in) :: t                !! new time
        self%t_base = t
        self%k_since = 0
    end subroutine stepper_set_time

    !> Steps completed since init.
    pure integer(ik) function stepper_steps(self)
        class(stepper_t), intent(in) :: self  !! the stepper
        stepper_steps = self%nsteps
    end function stepper_steps

    !> Force evaluations since init (first-same-as-last reuse not counted).
    pure integer(ik) function stepper_force_evaluations(self)
        class(stepper_t), intent(in) :: self  !! the stepper
        stepper_force_evaluations = self%nforce
    end function stepper_force_evaluations

    !> Gradient-term evaluations since init.
    pure integer(ik) function stepper_gradient_evaluations(self)
        class(stepper_t), intent(in) :: self  !! the stepper
        stepper_gradient_evaluations = self%ngrad
    end function stepper_gradient_evaluations

    !> Method label.
    pure function stepper_name(self) result(name)
        class(stepper_t), intent(in) :: self  !! the stepper
        character(len=:), allocatable :: name
        if (allocated(self%label)) then
            name = self%label
        else
            name = ''
        end if
    end function stepper_name

    !> True for splitting methods; false for RKN.
    pure logical function stepper_is_splitting(self)
        class(stepper_t), intent(in) :: self  !! the stepper
        stepper_is_splitting = self%splitting
    end function stepper_is_splitting

    !> True when every drift and kick weight is non-negative (a forward method).
    pure logical function stepper_is_forward(self)
        class(stepper_t), intent(in) :: self  !! the stepper
        stepper_is_forward = self%forward
    end function stepper_is_forward

    !> True when the step map is symplectic for every force.
    pure logical function stepper_is_symplectic(self)
        class(stepper_t), intent(in) :: self  !! the stepper
        stepper_is_symplectic = self%symplectic
    end function stepper_is_symplectic

    !> Force evaluations per step in steady state.
    pure integer function stepper_forces_per_step(self)
        class(stepper_t), intent(in) :: self  !! the stepper
        stepper_forces_per_step = self%nf_step
    end function stepper_forces_per_step

    !> Gradient evaluations per step.
    pure integer function stepper_gradients_per_step(self)
        class(stepper_t), intent(in) :: self  !! the stepper
        stepper_gradients_per_step = self%ng_step
    end function stepper_gradients_per_step

    !> Dimensions d and particles n the stepper was set up for.
    pure subroutine stepper_dims(self, d, n)
        class(stepper_t), intent(in) :: self  !! the stepper
        integer, intent(out) :: d, n          !! dimensions, particles
        d = self%d; n = self%n
    end subroutine stepper_dims

    !> For extensions: set the description and shape, reset clock and counters.
    subroutine describe_stepper(self, label, d, n, splitting, forward, symplectic, nf, ng, t0)
        class(stepper_t), intent(inout) :: self     !! the stepper
        character(len=*), intent(in) :: label       !! method label
        integer, intent(in) :: d, n                 !! dimensions, particles
        logical, intent(in) :: splitting, forward, symplectic  !! properties
        integer, intent(in) :: nf, ng               !! evaluations per step
        real(wp), intent(in) :: t0                  !! start time
        self%label = label
        self%d = d; self%n = n
        self%splitting = splitting; self%forward = forward; self%symplectic = symplectic
        self%nf_step = nf; self%ng_step = ng
        self%nsteps = 0; self%nforce = 0; self%ngrad = 0
        self%t_base = t0; self%k_since = 0; self%h_now = 0.0_wp
    end subroutine describe_stepper

    !> For extensions: one step (or `nsteps` steps) of size h completed.
    pure subroutine count_step(self, h, nsteps)
        class(stepper_t), intent(inout) :: self        !! the stepper
        real(wp), intent(in) :: h                      !! their size
        integer(ik), intent(in), optional :: nsteps    !! steps completed (default 1)
        integer(ik) :: k
        k = 1
        if (present(nsteps)) k = nsteps
        call self%account(self%nforce, self%ngrad, h, k)
    end subroutine count_step

    !> For extensions: store the evaluation counters (nf, ng: totals since init) and count
    !> k steps of size h (`counters` with mode 1, then `count_step`, in one call).
    pure subroutine account(self, nf, ng, h, k)
        class(stepper_t), intent(inout) :: self  !! the stepper
        integer(ik), intent(in) :: nf, ng        !! force and gradient evaluations since init
        real(wp), intent(in) :: h                !! step size
        integer(ik), intent(in) :: k             !! steps completed
        self%nforce = nf; self%ngrad = ng
        if (k < 1) return
        if (.not. fsym_same(h, self%h_now)) then
            self%t_base = self%time()
            self%k_since = 0
            self%h_now = h
        end if
        self%k_since = self%k_since + k
        self%nsteps = self%nsteps + k
    end subroutine account

    !> For extensions: the evaluation counters, to be updated in place by the kernel.
    subroutine counters(self, nf, ng, mode)
        class(stepper_t), intent(inout) :: self  !! the stepper
        integer(ik), intent(inout) :: nf, ng     !! local copies
        integer, intent(in) :: mode              !! 0: read into nf, ng; 1: store them
        if (mode == 0) then
            nf = self%nforce; ng = self%ngrad
        else
            self%nforce = nf; self%ngrad = ng
        end if
    end subroutine counters

    !> For extensions: record whether the observer stopped the run (`run_to` reads it).
    pure subroutine note_stop(self, stopped)
        class(stepper_t), intent(inout) :: self  !! the stepper
        logical, intent(in) :: stopped           !! the observer asked to stop
        self%stopped = stopped
    end subroutine note_stop

    !> For extensions (checkpoints): read (mode 0) or set (mode 1) the clock, time =
    !> t_base + k_since h_now, and the step count, bit for bit.
    subroutine clock_state(self, t_base, h_now, k_since, steps, mode)
        class(stepper_t), intent(inout) :: self      !! the stepper
        real(wp), intent(inout) :: t_base, h_now     !! clock base and step size
        integer(ik), intent(inout) :: k_since, steps !! steps at h_now, steps since init
        integer, intent(in) :: mode                  !! 0: read; 1: set
        if (mode == 0) then
            t_base = self%t_base; h_now = self%h_now; k_since = self%k_since
            steps = self%nsteps
        else
            self%t_base = t_base; self%h_now = h_now; self%k_since = k_since
            self%nsteps = steps
        end if
    end subroutine clock_state

end module fsym_stepper
