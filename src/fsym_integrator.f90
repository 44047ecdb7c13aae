!> The splitting integrator: owns a scheme and all its workspace, and drives the one kernel
!> with a user force model. `init` allocates; `step` and `run` never do.
module fsym_integrator
    use, intrinsic :: iso_c_binding, only: c_loc, c_intptr_t
    use fsym_kinds, only: wp, ik, fsym_same
    use fsym_status
    use fsym_scheme, only: scheme_t, fsym_scheme_custom, fsym_op_name
    use fsym_paper_schemes, only: fsym_scheme_by_name
    use fsym_force, only: force_model_t, recorder_t
    use fsym_stepper, only: stepper_t, observer_t
    use fsym_kernel, only: kernel_state_t, fsym_kernel_layout, fsym_kernel_run, &
                           fsym_kernel_invalidate, fsym_kernel_abort, fsym_kernel_slots, &
                           fsym_kernel_counts, fsym_kernel_stage
    use fsym_text, only: fsym_text_put, fsym_text_put_int
    use fsym_guard, only: guard_t, fsym_guard_setup, fsym_guard_message, fsym_guard_run
    use fsym_checkpoint, only: ckpt_clock_t, fsym_checkpoint_length, fsym_checkpoint_pack, &
                               fsym_checkpoint_unpack
    implicit none
    private

    public :: fsym_overlap

    !> A splitting integrator: scheme + workspace + kernel state.
    type, extends(stepper_t), public :: integrator_t
        private
        type(scheme_t) :: sc
        real(wp), allocatable :: w(:)        ! the kernel's work array (d, n, slots) from w(w0)
        integer :: w0 = 1                    ! w(w0) on a 64-byte boundary (vector loads)
        type(kernel_state_t) :: ks           ! the kernel's state
        integer :: nd = 0, nb = 0            ! the arrays' shape (d, n)
        integer(ik) :: nw = 0                ! reals of the work array in use
        logical :: ready = .false.
        logical :: needs_g = .false.        ! the scheme has gradient kicks
        type(guard_t) :: guard              ! the step-size guard (off by default)
        logical :: busy = .false.           ! a step is in progress (re-entry is refused)
        logical :: comp = .false.           ! compensated updates
        logical :: can_undo = .false.       ! the last call was one completed `step`
        type(ckpt_clock_t) :: clock0        ! the clock before it
        character(len=160) :: model_msg = ''  ! the model's text of the last failed step
    contains
        procedure :: init => integrator_init
            !! set up for a scheme, a model and arrays (d, n)
        procedure :: init_by_name => integrator_init_by_name
            !! `init` with the method given by its label
        procedure :: step => integrator_step
            !! one step of size h; on failure q, v unchanged
        procedure :: run_steps => integrator_run
            !! `run`: nsteps steps of size h in one kernel call; stops at the first failure
        procedure :: destroy => integrator_destroy      !! release the workspace
        procedure :: scheme => integrator_scheme        !! the scheme in use
        procedure :: reset_cache => integrator_reset_cache  !! forget the cached end-of-step force
        procedure :: work_size => integrator_work_size  !! reals of workspace held
        procedure :: checkpoint_length => integrator_checkpoint_length
            !! length of the flat checkpoint array
        procedure :: save_checkpoint => integrator_save_checkpoint
            !! the complete state into a flat array (see `fsym_checkpoint`)
        procedure :: load_checkpoint => integrator_load_checkpoint
            !! resume from a flat array: bitwise as if never interrupted
        procedure :: set_guard => integrator_set_guard
            !! turn the step-size guard on or off
        procedure :: in_use => integrator_in_use
            !! true while a step is in progress (inside the force model's calls)
        procedure :: undo_step => integrator_undo_step
            !! take back the step just completed by `step` (e.g. another MPI rank failed)
    end type integrator_t

contains

    !> Set up for `scheme` on arrays of shape (d, n). A scheme that needs the gradient term
    !> and a model without it is an error, unless `extrapolate` asks for the extrapolated
    !> form (A -> A', C -> C', AN -> AN'). `compensated` turns on Kahan-compensated updates of
    !> q and v. On error the integrator is left as it was.
    subroutine integrator_init(self, scheme, model, d, n, stat, errmsg, extrapolate, &
                               compensated, t0)
        class(integrator_t), intent(inout) :: self            !! the integrator
        type(scheme_t), intent(in) :: scheme                  !! method
        class(force_model_t), intent(in) :: model             !! force model it will be used with
        integer, intent(in) :: d, n                           !! dimensions, particles
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        logical, intent(in), optional :: extrapolate          !! use the extrapolated gradient
        logical, intent(in), optional :: compensated          !! compensated summation
        real(wp), intent(in), optional :: t0                  !! start time (default 0)
        type(scheme_t) :: s
        type(kernel_state_t) :: ks
        integer :: st, ast
        character(len=256) :: msg
        logical :: comp

        if (self%busy) then
            call fsym_report(FSYM_ERR_BUSY, 'init called from inside a step of the same '// &
                             'integrator', stat, errmsg)
            return
        end if
        if (d < 1 .or. n < 1) then
            call fsym_report(FSYM_ERR_SHAPE, 'need d >= 1 and n >= 1', stat, errmsg); return
        end if
        if (.not. allocated(scheme%op)) then
            call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'the scheme is empty', stat, errmsg)
            return
        end if
        ! re-check the table: a user may have edited a scheme's arrays
        call fsym_scheme_custom(scheme%name, scheme%op, scheme%c, scheme%u, scheme%order, s, &
                                st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        if (present(extrapolate)) then
            if (extrapolate) s = s%extrapolated()
        end if
        if (s%needs_gradient() .and. .not. model%has_gradient()) then
            call fsym_report(FSYM_ERR_NO_GRADIENT, 'method '//s%name// &
                             ' needs grad |a|^2: override gradient and has_gradient in the'// &
                             ' model (doc/pages/force.md), or pass extrapolate=.true. to run '// &
                             s%name//'''', stat, errmsg)
            return
        end if
        comp = .false.
        if (present(compensated)) comp = compensated
        call fsym_kernel_layout(s%op, comp, d, n, ks)

        self%ready = .false.
        if (allocated(self%w)) deallocate (self%w)
        allocate (self%w(int(d, ik) * n * fsym_kernel_slots(ks) + 7), stat=ast)
        if (ast /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'integrator workspace of '// &
                             fsym_int_text(fsym_kernel_slots(ks))//' x '//fsym_int_text(d)// &
                             ' x '//fsym_int_text(n)//' reals', stat, errmsg)
            return
        end if
        self%sc = s
        self%ks = ks
        self%nd = d; self%nb = n; self%nw = int(d, ik) * n * fsym_kernel_slots(ks)
        self%w = 0.0_wp
        self%w0 = aligned_start(self%w)
        call self%describe_stepper(s%name, d, n, .true., s%forward, s%symplectic, s%nforce, &
                                   s%ngrad, 0.0_wp)
        if (present(t0)) call self%set_time(t0)
        self%needs_g = s%needs_gradient()
        self%comp = comp
        self%can_undo = .false.
        self%guard%on = .false.             ! a new set-up starts unguarded
        self%ready = .true.
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine integrator_init

    !> `init` with the method given by its label (see `fsym_scheme_by_name`).
    subroutine integrator_init_by_name(self, name, model, d, n, stat, errmsg, extrapolate, &
                                       compensated, t0)
        class(integrator_t), intent(inout) :: self            !! the integrator
        character(len=*), intent(in) :: name                  !! method label
        class(force_model_t), intent(in) :: model             !! force model
        integer, intent(in) :: d, n                           !! dimensions, particles
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        logical, intent(in), optional :: extrapolate          !! use the extrapolated gradient
        logical, intent(in), optional :: compensated          !! compensated summation
        real(wp), intent(in), optional :: t0                  !! start time (default 0)
        type(scheme_t) :: s
        integer :: st
        character(len=256) :: msg
        call fsym_scheme_by_name(name, s, st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        call self%init(s, model, d, n, stat, errmsg, extrapolate, compensated, t0)
    end subroutine integrator_init_by_name

    !> One step of size h (negative steps run backward). On failure q, v are unchanged.
    subroutine integrator_step(self, model, q, v, h, stat, errmsg, recorder)
        class(integrator_t), intent(inout) :: self            !! the integrator
        class(force_model_t), intent(inout) :: model          !! force model
        real(wp), intent(inout), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(inout), contiguous :: v(:, :)        !! velocities (d, n)
        real(wp), intent(in) :: h                             !! step
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        class(recorder_t), intent(inout), optional :: recorder  !! force-point recorder
        integer(ik) :: ndone
        integer :: st
        st = refusal(self, q, v)
        if (st == FSYM_SUCCESS) then
            self%can_undo = .false.
            call self%clock_state(self%clock0%t_base, self%clock0%h_now, &
                                  self%clock0%k_since, self%clock0%steps, 0)
            self%busy = .true.
            call advance(self, model, q, v, h, 1_ik, ndone, st, recorder)
            self%busy = .false.
            self%can_undo = st == FSYM_SUCCESS
        end if
        if (st /= FSYM_SUCCESS) then
            call report(self, q, v, st, stat, errmsg); return
        end if
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine integrator_step

    !> Take back the step just completed by `step` (the last call on this integrator): q and
    !> v as at its start (bitwise, from the copies the kernel keeps), the clock and the step
    !> count as before it, the cached force forgotten; the evaluation counters keep the
    !> evaluations made. For a caller that learns after the step that it must not stand (an
    !> MPI rank whose step succeeded while another's failed). Only once, and only right after
    !> `step` with the same q and v: otherwise FSYM_ERR_BAD_REQUEST and nothing changes.
    subroutine integrator_undo_step(self, q, v, stat, errmsg)
        class(integrator_t), intent(inout) :: self            !! the integrator
        real(wp), intent(inout), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(inout), contiguous :: v(:, :)        !! velocities (d, n)
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer :: st
        st = refusal(self, q, v)
        if (st /= FSYM_SUCCESS) then
            call report(self, q, v, st, stat, errmsg); return
        end if
        if (.not. self%can_undo) then
            call fsym_report(FSYM_ERR_BAD_REQUEST, 'undo_step: the last call was not a '// &
                             'completed step (or it was undone already)', stat, errmsg)
            return
        end if
        call undo(self, q, v)
        self%can_undo = .false.
        call self%clock_state(self%clock0%t_base, self%clock0%h_now, self%clock0%k_since, &
                              self%clock0%steps, 1)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine integrator_undo_step

    !> The kernel's undo on arrays of the integrator's shape.
    subroutine undo(self, q, v)
        class(integrator_t), intent(inout) :: self
        real(wp), intent(inout) :: q(self%nd, self%nb), v(self%nd, self%nb)
        call fsym_kernel_abort(self%ks, q, v, self%w(self%w0), completed=.true.)
    end subroutine undo

    !> `nsteps` steps of size h; stops at the first failing step, leaving the state of the
    !> last good step (check `stat`; `steps()` tells how far it got). Bitwise the same as
    !> `nsteps` calls of `step`: the kernel takes the steps in one call (per `every` steps
    !> when an observer looks at the state; it may stop the run).
    subroutine integrator_run(self, model, q, v, h, nsteps, stat, errmsg, recorder, observer, &
                              every)
        class(integrator_t), intent(inout) :: self            !! the integrator
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
        integer(ik) :: left, chunk, ndone
        integer :: st
        logical :: stop
        if (self%busy) then
            call report(self, q, v, FSYM_ERR_BUSY, stat, errmsg); return
        end if
        self%can_undo = .false.
        call self%note_stop(.false.)
        if (nsteps < 1) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'run: nsteps = '//fsym_int_text(nsteps)// &
                             ' (must be >= 1)', stat, errmsg)
            return
        end if
        st = refusal(self, q, v)
        if (st /= FSYM_SUCCESS) then
            call report(self, q, v, st, stat, errmsg); return
        end if
        if (.not. present(observer)) then
            self%busy = .true.
            call advance(self, model, q, v, h, nsteps, ndone, st, recorder)
            self%busy = .false.
            if (st /= FSYM_SUCCESS) then
                call report(self, q, v, st, stat, errmsg); return
            end if
            if (present(stat)) stat = FSYM_SUCCESS
            return
        end if
        chunk = 1
        if (present(every)) chunk = max(1, every)
        left = nsteps
        if (present(stat)) stat = FSYM_SUCCESS
        do while (left > 0)
            self%busy = .true.     ! not while the observer looks: it may save a checkpoint
            call advance(self, model, q, v, h, min(chunk, left), ndone, st, recorder)
            self%busy = .false.
            if (st /= FSYM_SUCCESS) call report(self, q, v, st, stat, errmsg)
            if (present(stat)) stat = st
            if (st /= FSYM_SUCCESS .or. ndone < min(chunk, left)) return
            left = left - ndone
            if (ndone == chunk) then
                stop = .false.
                call observer%observe_model(model, q, v, self%time(), self%steps(), stop)
                call self%note_stop(stop)
                if (stop) return
            end if
        end do
    end subroutine integrator_run

    !> FSYM_SUCCESS when the integrator is set up for arrays of the shape of q and v, is not
    !> in a step already (FSYM_ERR_BUSY: a force model that steps its own integrator), and q
    !> and v do not share memory (FSYM_ERR_BAD_ARGUMENT); else why a step is refused.
    integer function refusal(self, q, v) result(st)
        class(integrator_t), intent(in) :: self
        real(wp), intent(in), contiguous :: q(:, :), v(:, :)
        st = FSYM_SUCCESS
        if (self%busy) then
            st = FSYM_ERR_BUSY
        else if (.not. (self%ready .and. size(q, 1) == self%nd .and. size(q, 2) == self%nb &
                        .and. size(v, 1) == self%nd .and. size(v, 2) == self%nb)) then
            st = merge(FSYM_ERR_SHAPE, FSYM_ERR_NOT_INITIALIZED, self%ready)
        else if (fsym_overlap(q, v)) then
            st = FSYM_ERR_BAD_ARGUMENT
        end if
    end function refusal

    !> Whether two contiguous arrays share memory (by address: the same array passed as q
    !> and as v, or overlapping sections of one array).
    logical function fsym_overlap(x, y)
        real(wp), intent(in), contiguous, target :: x(:, :)  !! first array
        real(wp), intent(in), contiguous, target :: y(:, :)  !! second array
        integer(c_intptr_t) :: ax, ay, nx, ny
        fsym_overlap = .false.
        if (size(x) == 0 .or. size(y) == 0) return
        ax = transfer(c_loc(x), ax); ay = transfer(c_loc(y), ay)
        nx = size(x, kind=c_intptr_t) * (storage_size(x) / 8)
        ny = size(y, kind=c_intptr_t) * (storage_size(y) / 8)
        fsym_overlap = ax < ay + ny .and. ay < ax + nx
    end function fsym_overlap

    !> Up to `nsteps` steps in one kernel call, with the checks a call makes, the clock and
    !> the counters, on arrays of the integrator's shape (`refusal` has checked it; explicit
    !> shape, so no array descriptor is made per call). `st`: a status code (the caller
    !> reports a failure with `report`). The common path is short: no messages, the guard
    !> and the recorder apart.
    subroutine advance(self, model, q, v, h, nsteps, ndone, st, recorder)
        class(integrator_t), intent(inout) :: self
        class(force_model_t), intent(inout) :: model
        real(wp), intent(inout) :: q(self%nd, self%nb), v(self%nd, self%nb)
        real(wp), intent(in) :: h
        integer(ik), intent(in) :: nsteps
        integer(ik), intent(out) :: ndone
        integer, intent(out) :: st
        class(recorder_t), intent(inout), optional :: recorder
        integer(ik) :: nf, ng
        ndone = 0; st = FSYM_SUCCESS
        if (self%needs_g) then
            if (.not. model%has_gradient()) then
                st = FSYM_ERR_NO_GRADIENT; return
            end if
        end if
        if (self%guard%on .or. present(recorder)) then
            call watched_run(self, model, q, v, h, nsteps, ndone, st, recorder)
        else
            call fsym_kernel_run(self%sc%nop, self%sc%op, self%sc%c, self%sc%u, model, &
                                 self%ks, q, v, self%w(self%w0), h, nsteps, ndone, st, &
                                 t0=self%time())
        end if
        call fsym_kernel_counts(self%ks, nf, ng)
        call self%account(nf, ng, h, ndone)
        if (st == FSYM_ERR_MODEL) then      ! the model may say more (a close encounter)
            self%model_msg = ''
            call model%failure(st, self%model_msg)
        end if
    end subroutine advance

    !> Report the status `st` of `advance`: a refusal (not initialised, arrays of the wrong
    !> shape, no gradient term), the guard's refusal, or a failing step (the state is that
    !> of the last good step).
    subroutine report(self, q, v, st, stat, errmsg)
        class(integrator_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :), v(:, :)
        integer, intent(in) :: st
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        select case (st)
        case (FSYM_ERR_NOT_INITIALIZED)
            call fsym_report(st, 'integrator_t%step before init', stat, errmsg)
        case (FSYM_ERR_BUSY)
            call fsym_report(st, 'a step of this integrator is in progress: its force '// &
                             'model called it again (re-entry refused, nothing changed)', &
                             stat, errmsg)
        case (FSYM_ERR_BAD_ARGUMENT)
            call fsym_report(st, 'q and v share memory (the same array, or overlapping '// &
                             'sections, passed as both); nothing changed', stat, errmsg)
        case (FSYM_ERR_SHAPE)
            call fsym_report(st, trim(shape_text(self%nd, self%nb, q, v)), stat, errmsg)
        case (FSYM_ERR_NO_GRADIENT)
            call fsym_report(st, 'method '//self%sc%name//': this model has no gradient term', &
                             stat, errmsg)
        case (FSYM_ERR_STEP_TOO_LARGE)
            call fsym_report(st, fsym_guard_message(self%guard, self%sc%name, self%time(), &
                             self%steps() + 1), stat, errmsg)
        case default
            call report_step_failure(self, st, fsym_kernel_stage(self%ks) == 0, q, v, stat, errmsg)
        end select
    end subroutine report

    !> The kernel with a recorder, or with the guard (step by step); no fused model steps.
    subroutine watched_run(self, model, q, v, h, nsteps, ndone, st, recorder)
        class(integrator_t), intent(inout) :: self
        class(force_model_t), intent(inout) :: model
        real(wp), intent(inout) :: q(self%nd, self%nb), v(self%nd, self%nb)
        real(wp), intent(in) :: h
        integer(ik), intent(in) :: nsteps
        integer(ik), intent(out) :: ndone
        integer, intent(out) :: st
        class(recorder_t), intent(inout), optional :: recorder
        if (self%guard%on) then
            call guarded_run(self, model, q, v, h, nsteps, ndone, st, recorder, self%steps())
        else
            call fsym_kernel_run(self%sc%nop, self%sc%op, self%sc%c, self%sc%u, model, &
                                 self%ks, q, v, self%w(self%w0), h, nsteps, ndone, st, recorder, &
                                 self%steps(), t0=self%time())
        end if
    end subroutine watched_run

    !> The kernel step by step under the guard (`fsym_guard_run`: every step checked at its
    !> start, at every drift and at its end; a refused step is undone, the state intact).
    subroutine guarded_run(self, model, q, v, h, nsteps, ndone, st, recorder, step0)
        class(integrator_t), intent(inout) :: self
        class(force_model_t), intent(inout), target :: model
        real(wp), intent(inout), contiguous :: q(:, :), v(:, :)
        real(wp), intent(in) :: h
        integer(ik), intent(in) :: nsteps, step0
        integer(ik), intent(out) :: ndone
        integer, intent(out) :: st
        class(recorder_t), intent(inout), optional :: recorder
        call fsym_guard_run(self%guard, self%sc%nop, self%sc%op, self%sc%c, self%sc%u, model, &
                            self%ks, q, v, self%w(self%w0:), h, nsteps, ndone, st, self%comp, &
                            recorder, step0, t0=self%time())
    end subroutine guarded_run

    !> Turn the step-size guard on (`on`) or off. On, every step first asks the model for its
    !> largest local frequency omega (`local_frequency`, e.g. omega^2 = 2 mu/r^3 for Kepler)
    !> and refuses a step with |h| omega > fraction x*, x* being the end of the method's
    !> stability interval on the harmonic oscillator (from its own coefficient table,
    !> `fsym_stability_interval`): status FSYM_ERR_STEP_TOO_LARGE, a message with the time,
    !> r, h omega and x*, and the state intact. `fraction` (default 1) tightens the limit.
    !> A model without `local_frequency` cannot be guarded (FSYM_ERR_BAD_ARGUMENT).
    subroutine integrator_set_guard(self, model, on, stat, errmsg, fraction)
        class(integrator_t), intent(inout) :: self            !! the integrator
        class(force_model_t), intent(in) :: model             !! the force model to be used
        logical, intent(in) :: on                             !! guard on or off
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        real(wp), intent(in), optional :: fraction            !! of x* (default 1)
        integer :: st
        character(len=128) :: msg
        if (.not. self%ready) then
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'set_guard before init', stat, errmsg)
            return
        end if
        if (self%busy) then
            call fsym_report(FSYM_ERR_BUSY, 'set_guard inside a step', stat, errmsg); return
        end if
        if (.not. on) then
            self%guard%on = .false.
            if (present(stat)) stat = FSYM_SUCCESS
            return
        end if
        call fsym_guard_setup(self%guard, self%sc, model, st, msg, fraction)
        call fsym_pass(st, msg, stat, errmsg)
    end subroutine integrator_set_guard

    !> Report a failed step (rejected on entry when `at_begin`). The message is built in a
    !> fixed buffer without allocation (a failing step should not allocate to say why).
    subroutine report_step_failure(self, st, at_begin, q, v, stat, errmsg)
        class(integrator_t), intent(in) :: self
        integer, intent(in) :: st
        logical, intent(in) :: at_begin
        real(wp), intent(in) :: q(:, :), v(:, :)
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        character(len=320) :: buf
        integer :: k, p, pc
        pc = fsym_kernel_stage(self%ks)
        k = self%sc%op(max(1, min(pc, self%sc%nop)))
        p = 0; buf = ''
        call fsym_text_put(buf, p, 'method ')
        call fsym_text_put(buf, p, self%sc%name)
        call fsym_text_put(buf, p, ', step ')
        call fsym_text_put_int(buf, p, self%steps() + 1)
        if (.not. at_begin) then
            call fsym_text_put(buf, p, ', stage ')
            call fsym_text_put_int(buf, p, int(pc, ik))
            if (st == FSYM_ERR_NONFINITE_STATE) then
                call fsym_text_put(buf, p, ': the step drove the state to NaN/Inf (step &
                                   &too large for this state?); state restored')
            else
                call fsym_text_put(buf, p, ' (')
                call fsym_text_put(buf, p, fsym_op_name(k))
                call fsym_text_put(buf, p, '); state restored')
                if ((st == FSYM_ERR_MODEL .or. st == FSYM_ERR_ENCOUNTER) .and. &
                    len_trim(self%model_msg) > 0) then
                    call fsym_text_put(buf, p, '; ')
                    call fsym_text_put(buf, p, self%model_msg(1:len_trim(self%model_msg)))
                end if
            end if
        else if (st == FSYM_ERR_NONFINITE_STATE) then
            call fsym_text_put(buf, p, ': refused, ')
            call name_nonfinite(buf, p, 'q', q)
            if (all(abs(q) <= huge(q))) call name_nonfinite(buf, p, 'v', v)
            call fsym_text_put(buf, p, ' on entry (component, particle); nothing changed')
        end if
        call fsym_report(st, buf(1:p), stat, errmsg)
    end subroutine report_step_failure

    !> Append `name(i, j) = NaN` (or +Inf, -Inf) for the first value of x that is not finite.
    pure subroutine name_nonfinite(buf, p, name, x)
        character(len=*), intent(inout) :: buf
        integer, intent(inout) :: p
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: x(:, :)
        integer :: i, j
        do j = 1, size(x, 2)
            do i = 1, size(x, 1)
                if (abs(x(i, j)) <= huge(x)) cycle
                call fsym_text_put(buf, p, name//'(')
                call fsym_text_put_int(buf, p, int(i, ik))
                call fsym_text_put(buf, p, ', ')
                call fsym_text_put_int(buf, p, int(j, ik))
                call fsym_text_put(buf, p, ') = ')
                if (.not. fsym_same(x(i, j), x(i, j))) call fsym_text_put(buf, p, 'NaN')
                if (x(i, j) > huge(x)) call fsym_text_put(buf, p, '+Inf')
                if (x(i, j) < -huge(x)) call fsym_text_put(buf, p, '-Inf')
                return
            end do
        end do
    end subroutine name_nonfinite

    !> Release the workspace; `init` must be called again before use. Ignored while a step
    !> is in progress (from inside the force model: the step still uses the workspace).
    subroutine integrator_destroy(self)
        class(integrator_t), intent(inout) :: self  !! the integrator
        if (self%busy) return
        if (allocated(self%w)) deallocate (self%w)
        self%ready = .false.
    end subroutine integrator_destroy

    !> The scheme in use (after any extrapolation).
    function integrator_scheme(self) result(s)
        class(integrator_t), intent(in) :: self  !! the integrator
        type(scheme_t) :: s
        s = self%sc
    end function integrator_scheme

    !> Forget the cached end-of-step force. Not needed after changing q (that is detected),
    !> only after changing the force model's own parameters between steps.
    subroutine integrator_reset_cache(self)
        class(integrator_t), intent(inout) :: self  !! the integrator
        if (.not. self%busy) call fsym_kernel_invalidate(self%ks)
    end subroutine integrator_reset_cache

    !> True while a step of this integrator is in progress (its force model is being called).
    pure logical function integrator_in_use(self)
        class(integrator_t), intent(in) :: self  !! the integrator
        integrator_in_use = self%busy
    end function integrator_in_use

    !> Reals of workspace held (d * n * slots).
    pure integer(ik) function integrator_work_size(self)
        class(integrator_t), intent(in) :: self  !! the integrator
        integer(ik) :: m
        m = 0
        if (allocated(self%w)) m = self%nw
        integrator_work_size = m
    end function integrator_work_size

    !> Length of the checkpoint array of this integrator (0 before init).
    pure integer(ik) function integrator_checkpoint_length(self) result(m)
        class(integrator_t), intent(in) :: self  !! the integrator
        m = 0
        if (self%ready) m = fsym_checkpoint_length(self%sc%nop, self%nd, self%nb, &
                                                   fsym_kernel_slots(self%ks))
    end function integrator_checkpoint_length

    !> Write the complete state (q, v, clock, counters, method, cached forces, compensation
    !> terms) into `ck`, at least `checkpoint_length()` long. Between steps only.
    subroutine integrator_save_checkpoint(self, q, v, ck, stat, errmsg)
        class(integrator_t), intent(inout) :: self            !! the integrator
        real(wp), intent(in), contiguous :: q(:, :)           !! positions (d, n)
        real(wp), intent(in), contiguous :: v(:, :)           !! velocities (d, n)
        real(wp), intent(out) :: ck(:)                        !! the checkpoint
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        type(ckpt_clock_t) :: clock
        if (.not. checkpoint_fits(self, q, v, size(ck, kind=ik), stat, errmsg)) return
        call self%clock_state(clock%t_base, clock%h_now, clock%k_since, clock%steps, 0)
        call fsym_checkpoint_pack(self%sc%op, self%sc%c, self%sc%u, self%ks, clock, q, v, &
                                  self%w(self%w0:self%w0 + self%nw - 1), ck)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine integrator_save_checkpoint

    !> Resume from a checkpoint written by `save_checkpoint` (or by another face) of the same
    !> method on the same arrays: q, v, the clock, the counters and the kernel state are
    !> restored, so the run goes on bitwise as if never interrupted. The integrator must be
    !> set up (`init`) for the same method, shape and compensation; the force model must be
    !> in the same state as when the checkpoint was written. On error nothing changes.
    subroutine integrator_load_checkpoint(self, q, v, ck, stat, errmsg)
        class(integrator_t), intent(inout) :: self            !! the integrator
        real(wp), intent(inout), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(inout), contiguous :: v(:, :)        !! velocities (d, n)
        real(wp), intent(in) :: ck(:)                         !! the checkpoint
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        type(ckpt_clock_t) :: clock
        integer :: st
        integer(ik) :: nf, ng
        character(len=128) :: msg
        if (.not. checkpoint_fits(self, q, v, size(ck, kind=ik), stat, errmsg)) return
        call fsym_checkpoint_unpack(ck, self%sc%op, self%sc%c, self%sc%u, self%ks, clock, q, &
                                    v, self%w(self%w0:self%w0 + self%nw - 1), st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_report(st, msg, stat, errmsg); return
        end if
        call self%clock_state(clock%t_base, clock%h_now, clock%k_since, clock%steps, 1)
        self%can_undo = .false.
        call fsym_kernel_counts(self%ks, nf, ng)
        call self%counters(nf, ng, 1)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine integrator_load_checkpoint

    !> The checks a checkpoint call makes: set up, shapes, length of ck.
    logical function checkpoint_fits(self, q, v, nck, stat, errmsg) result(ok)
        class(integrator_t), intent(in) :: self
        real(wp), intent(in), contiguous :: q(:, :), v(:, :)
        integer(ik), intent(in) :: nck
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        ok = .false.
        if (.not. self%ready) then
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'checkpoint before init', stat, errmsg)
        else if (self%busy) then
            call fsym_report(FSYM_ERR_BUSY, 'checkpoint inside a step (from the force model)', &
                             stat, errmsg)
        else if (size(q, 1) /= self%nd .or. size(q, 2) /= self%nb .or. &
                 size(v, 1) /= self%nd .or. size(v, 2) /= self%nb) then
            call fsym_report(FSYM_ERR_SHAPE, trim(shape_text(self%nd, self%nb, q, v)), stat, &
                             errmsg)
        else if (fsym_overlap(q, v)) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'q and v share memory', stat, errmsg)
        else if (nck < self%checkpoint_length()) then
            call fsym_report(FSYM_ERR_CHECKPOINT, 'checkpoint array shorter than '// &
                             fsym_int_text(self%checkpoint_length()), stat, errmsg)
        else
            ok = .true.
        end if
    end function checkpoint_fits

    !> The index of the first value of x on a 64-byte boundary (x holds at least 8 values).
    integer function aligned_start(x) result(k)
        real(wp), intent(in), target :: x(:)
        integer(c_intptr_t) :: addr
        addr = transfer(c_loc(x(1)), addr)
        k = 1 + int(modulo(-addr, 64_c_intptr_t) / (storage_size(x) / 8))
    end function aligned_start

    !> The shapes expected and given, in a fixed-length result (a deferred-length result
    !> would keep its length in a static variable of the caller, shared by threads).
    function shape_text(d, n, q, v) result(s)
        integer, intent(in) :: d, n
        real(wp), intent(in) :: q(:, :), v(:, :)
        character(len=128) :: s
        write (s, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a)') 'expected (', d, ',', n, &
            '), got q(', size(q, 1), ',', size(q, 2), ') and v(', size(v, 1), ',', size(v, 2), ')'
    end function shape_text

end module fsym_integrator
