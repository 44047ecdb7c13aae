!> The splitting integrator: owns a scheme and all its workspace, and drives the one kernel
!> with a user force model. `init` allocates; `step` and `run` never do.
module fsym_integrator
    use fsym_kinds, only: wp, ik
    use fsym_status
    use fsym_scheme, only: scheme_t, fsym_scheme_custom, fsym_op_name
    use fsym_paper_schemes, only: fsym_scheme_by_name
    use fsym_force, only: force_model_t, recorder_t, EVAL_FORCE, EVAL_GRADIENT, &
                          EVAL_EXTRAPOLATED
    use fsym_stepper, only: stepper_t, stepper_run
    use fsym_kernel
    use fsym_kepler, only: kepler_model_t
    implicit none
    private

    !> A splitting integrator: scheme + workspace + kernel state.
    type, extends(stepper_t), public :: integrator_t
        private
        type(scheme_t) :: sc
        real(wp), allocatable :: w(:, :, :)
        integer :: iw(KERNEL_NIW) = 0
        real(wp) :: rw(KERNEL_NRW) = 0.0_wp
        integer :: nslot = 0
        logical :: ready = .false.
        logical :: needs_g = .false.        ! the scheme has gradient kicks
    contains
        procedure :: init => integrator_init
            !! set up for a scheme, a model and arrays (d, n)
        procedure :: init_by_name => integrator_init_by_name
            !! `init` with the method given by its label
        procedure :: step => integrator_step
            !! one step of size h; on failure q, v unchanged
        procedure :: run => integrator_run
            !! nsteps steps of size h; stops at the first failing step
        procedure :: destroy => integrator_destroy      !! release the workspace
        procedure :: scheme => integrator_scheme        !! the scheme in use
        procedure :: reset_cache => integrator_reset_cache  !! forget the cached end-of-step force
        procedure :: work_size => integrator_work_size  !! reals of workspace held
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
        integer :: st, iw(KERNEL_NIW), nslot
        real(wp) :: rw(KERNEL_NRW)
        character(len=256) :: msg
        logical :: comp

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
                             ' needs the gradient term; give the model a gradient or pass'// &
                             ' extrapolate=.true. for '//s%name//'''', stat, errmsg)
            return
        end if
        comp = .false.
        if (present(compensated)) comp = compensated
        call fsym_kernel_layout(s%op, comp, iw, rw, nslot)

        self%sc = s
        self%iw = iw
        self%rw = rw
        self%nslot = nslot
        if (allocated(self%w)) deallocate (self%w)
        allocate (self%w(d, n, nslot))
        self%w = 0.0_wp
        call self%describe_stepper(s%name, d, n, .true., s%forward, s%symplectic, s%nforce, &
                                   s%ngrad, 0.0_wp)
        if (present(t0)) call self%set_time(t0)
        self%needs_g = s%needs_gradient()
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
        integer :: d, n, st, req, mst, ia, ig, iqe, iae
        integer(ik) :: nf, ng, istep
        logical :: ok, taken

        if (.not. self%ready) then
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'integrator_t%step before init', stat, &
                             errmsg)
            return
        end if
        call self%dims(d, n)
        call check_shapes(d, n, q, v, ok, stat, errmsg)
        if (.not. ok) return
        call kepler_steps(self, model, d, n, q, v, h, 1_ik, present(recorder), taken, stat, &
                          errmsg)
        if (taken) return
        if (self%needs_g) then
            if (.not. model%has_gradient()) then
                call fsym_report(FSYM_ERR_NO_GRADIENT, 'method '//self%sc%name// &
                                 ': this model has no gradient term', stat, errmsg)
                return
            end if
        end if
        call fsym_kernel_begin(d, n, q, v, h, self%w, self%nslot, self%iw, self%rw, st)
        if (st /= FSYM_SUCCESS) then
            call report_step_failure(self, st, .true., stat, errmsg); return
        end if
        ia = fsym_kernel_slot(self%iw, SLOT_A); ig = fsym_kernel_slot(self%iw, SLOT_G)
        iqe = fsym_kernel_slot(self%iw, SLOT_QE); iae = fsym_kernel_slot(self%iw, SLOT_AE)
        call self%counters(nf, ng, 0)
        istep = self%steps() + 1
        do
            call fsym_kernel_resume(self%sc%nop, self%sc%op, self%sc%c, self%sc%u, d, n, q, v, &
                                    self%w, self%nslot, self%iw, self%rw, nf, ng, req, st)
            if (req == REQ_DONE .or. req == REQ_ERROR) exit
            mst = 0
            select case (req)
            case (REQ_FORCE)
                call model%acceleration(q, self%w(:, :, ia), mst)
                if (present(recorder)) call recorder%record(istep, self%iw(KW_PC), EVAL_FORCE, q)
            case (REQ_GRADIENT)
                call model%gradient(q, self%w(:, :, ia), self%w(:, :, ig), mst)
                if (present(recorder)) call recorder%record(istep, self%iw(KW_PC), EVAL_GRADIENT, q)
            case (REQ_FORCE_SHIFTED)
                call model%acceleration(self%w(:, :, iqe), self%w(:, :, iae), mst)
                if (present(recorder)) call recorder%record(istep, self%iw(KW_PC), &
                                                            EVAL_EXTRAPOLATED, self%w(:, :, iqe))
            case default
                ! nothing else can occur here
            end select
            if (mst /= 0) then
                call fsym_kernel_abort(d, n, q, v, self%w, self%nslot, self%iw)
                st = FSYM_ERR_MODEL
                exit
            end if
        end do
        call self%counters(nf, ng, 1)
        if (st /= FSYM_SUCCESS) then
            call report_step_failure(self, st, .false., stat, errmsg); return
        end if
        call self%count_step(h)
        if (present(stat)) stat = FSYM_SUCCESS

    end subroutine integrator_step

    !> `nsteps` steps of size h; stops at the first failing step, leaving the state of the
    !> last good step (check `stat`; `steps()` tells how far it got). Bitwise the same as
    !> `nsteps` calls of `step`; for the library's `kepler_model_t` the kernel takes all the
    !> steps in one call (see `kepler_steps`).
    subroutine integrator_run(self, model, q, v, h, nsteps, stat, errmsg, recorder)
        class(integrator_t), intent(inout) :: self            !! the integrator
        class(force_model_t), intent(inout) :: model          !! force model
        real(wp), intent(inout), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(inout), contiguous :: v(:, :)        !! velocities (d, n)
        real(wp), intent(in) :: h                             !! step
        integer(ik), intent(in) :: nsteps                     !! number of steps
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        class(recorder_t), intent(inout), optional :: recorder  !! force-point recorder
        integer :: d, n
        logical :: ok, taken
        if (self%ready) then
            call self%dims(d, n)
            call check_shapes(d, n, q, v, ok, stat, errmsg)
            if (.not. ok) return
            call kepler_steps(self, model, d, n, q, v, h, nsteps, present(recorder), taken, &
                              stat, errmsg)
            if (taken) return
        end if
        call stepper_run(self, model, q, v, h, nsteps, stat, errmsg, recorder)
    end subroutine integrator_run

    !> The specialised path for the library's Kepler model (exactly that type, not its
    !> extensions, which may override the force), without recorder or compensation: the
    !> kernel takes all `nsteps` steps in one call with the force called directly (no
    !> reverse communication, no dynamic dispatch per force, no return between steps); the
    !> same stage arithmetic as the general path, bitwise the same result. That model has
    !> the gradient term, so no check for it is needed. `taken` is false (and nothing done)
    !> for any other model, with a recorder, or with compensation.
    subroutine kepler_steps(self, model, d, n, q, v, h, nsteps, recorded, taken, stat, errmsg)
        class(integrator_t), intent(inout) :: self
        class(force_model_t), intent(in) :: model
        integer, intent(in) :: d, n
        real(wp), intent(inout) :: q(d, n), v(d, n)
        real(wp), intent(in) :: h
        integer(ik), intent(in) :: nsteps
        logical, intent(in) :: recorded
        logical, intent(out) :: taken
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        integer(ik) :: nf, ng, ndone
        integer :: st
        real(wp) :: mu
        taken = .false.
        if (recorded .or. self%iw(KW_COMP) /= 0) return
        select type (model)
        type is (kepler_model_t)
            mu = model%mu
        class default
            return
        end select
        taken = .true.
        call self%counters(nf, ng, 0)
        call fsym_kernel_run_kepler(self%sc%nop, self%sc%op, self%sc%c, self%sc%u, d, n, q, v, &
                                    h, mu, nsteps, self%w, self%nslot, self%iw, self%rw, &
                                    nf, ng, ndone, st)
        call self%counters(nf, ng, 1)
        call self%count_step(h, ndone)
        if (st /= FSYM_SUCCESS) then
            call report_step_failure(self, st, self%iw(KW_PC) == 0, stat, errmsg)
            return
        end if
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine kepler_steps

    !> Report a failed step (rejected on entry when `at_begin`).
    subroutine report_step_failure(self, st, at_begin, stat, errmsg)
        class(integrator_t), intent(in) :: self
        integer, intent(in) :: st
        logical, intent(in) :: at_begin
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        if (at_begin) then
            call fsym_report(st, 'method '//self%sc%name//', step '// &
                             fsym_int_text(self%steps() + 1), stat, errmsg)
        else
            call fsym_report(st, 'method '//self%sc%name//', step '// &
                             fsym_int_text(self%steps() + 1)//', stage '// &
                             fsym_int_text(self%iw(KW_PC))//' ('// &
                             fsym_op_name(self%sc%op(min(self%iw(KW_PC), self%sc%nop)))// &
                             '); state restored', stat, errmsg)
        end if
    end subroutine report_step_failure

    !> Release the workspace; `init` must be called again before use.
    subroutine integrator_destroy(self)
        class(integrator_t), intent(inout) :: self  !! the integrator
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
        call fsym_kernel_invalidate(self%iw)
    end subroutine integrator_reset_cache

    !> Reals of workspace held (d * n * slots).
    pure integer(ik) function integrator_work_size(self)
        class(integrator_t), intent(in) :: self  !! the integrator
        integer(ik) :: m
        m = 0
        if (allocated(self%w)) m = size(self%w, kind=ik)
        integrator_work_size = m
    end function integrator_work_size

    !> `ok` when q and v have the shape (d, n); else FSYM_ERR_SHAPE is reported.
    subroutine check_shapes(d, n, q, v, ok, stat, errmsg)
        integer, intent(in) :: d, n
        real(wp), intent(in) :: q(:, :), v(:, :)
        logical, intent(out) :: ok
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        ok = size(q, 1) == d .and. size(q, 2) == n .and. size(v, 1) == d .and. size(v, 2) == n
        if (.not. ok) call fsym_report(FSYM_ERR_SHAPE, shape_text(d, n, q, v), stat, errmsg)
    end subroutine check_shapes

    function shape_text(d, n, q, v) result(s)
        integer, intent(in) :: d, n
        real(wp), intent(in) :: q(:, :), v(:, :)
        character(len=:), allocatable :: s
        character(len=128) :: buf
        write (buf, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a)') 'expected (', d, ',', n, &
            '), got q(', size(q, 1), ',', size(q, 2), ') and v(', size(v, 1), ',', size(v, 2), ')'
        s = trim(buf)
    end function shape_text

end module fsym_integrator
