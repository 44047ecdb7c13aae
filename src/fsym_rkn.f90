!> The conventional fourth-order Runge-Kutta-Nystrom method of the paper (eqs. rkn, rknf),
!> the non-symplectic comparator. Not a splitting: three forces per step, no reuse.
!>
!>     F0 = a(q0);  q1' = q0 + h/2 v0 + (h/2)^2/2 F0;  F1 = a(q1')
!>     q2' = q0 + h v0 + h^2/2 F1;  F2 = a(q2')
!>     q = q0 + h v0 + h^2/6 (F0 + 2 F1);  v = v0 + h/6 (F0 + 4 F1 + F2)
module fsym_rkn
    use fsym_kinds, only: wp, ik
    use fsym_status
    use fsym_force, only: force_model_t, recorder_t, EVAL_FORCE
    use fsym_stepper, only: stepper_t
    use fsym_kernel, only: fsym_all_finite
    implicit none
    private

    !> The RKN stepper; same interface as the splitting integrator.
    type, extends(stepper_t), public :: rkn_t
        private
        real(wp), allocatable :: f0(:, :), f1(:, :), f2(:, :), qt(:, :)
        logical :: ready = .false.
    contains
        procedure :: init => rkn_init                   !! set up for arrays (d, n)
        procedure :: step => rkn_step                   !! one RKN step; on failure q, v unchanged
        procedure :: destroy => rkn_destroy             !! release the workspace
    end type rkn_t

contains

    !> Set up for arrays of shape (d, n).
    subroutine rkn_init(self, d, n, stat, errmsg, t0)
        class(rkn_t), intent(inout) :: self                   !! the stepper
        integer, intent(in) :: d, n                           !! dimensions, particles
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        real(wp), intent(in), optional :: t0                  !! start time (default 0)
        integer :: ast
        if (d < 1 .or. n < 1) then
            call fsym_report(FSYM_ERR_SHAPE, 'need d >= 1 and n >= 1', stat, errmsg); return
        end if
        self%ready = .false.
        call rkn_release(self)
        ! one allocation at a time: after a failure the rest are known to be unallocated
        allocate (self%f0(d, n), stat=ast)
        if (ast == 0) allocate (self%f1(d, n), stat=ast)
        if (ast == 0) allocate (self%f2(d, n), stat=ast)
        if (ast == 0) allocate (self%qt(d, n), stat=ast)
        if (ast /= 0) then
            call rkn_release(self)
            call fsym_report(FSYM_ERR_NO_MEMORY, 'RKN workspace of 4 x '//fsym_int_text(d)// &
                             ' x '//fsym_int_text(n)//' reals', stat, errmsg)
            return
        end if
        call self%describe_stepper('RKN', d, n, .false., .false., .false., 3, 0, 0.0_wp)
        if (present(t0)) call self%set_time(t0)
        self%ready = .true.
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine rkn_init

    !> One RKN step; on failure q, v are unchanged (the new state is formed only at the end).
    subroutine rkn_step(self, model, q, v, h, stat, errmsg, recorder)
        class(rkn_t), intent(inout) :: self                   !! the stepper
        class(force_model_t), intent(inout) :: model          !! force model
        real(wp), intent(inout), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(inout), contiguous :: v(:, :)        !! velocities (d, n)
        real(wp), intent(in) :: h                             !! step
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        class(recorder_t), intent(inout), optional :: recorder  !! force-point recorder
        integer :: d, n, st, mst
        integer(ik) :: nf, ng, istep

        if (.not. self%ready) then
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'rkn_t%step before init', stat, errmsg)
            return
        end if
        call self%dims(d, n)
        if (size(q, 1) /= d .or. size(q, 2) /= n .or. size(v, 1) /= d .or. size(v, 2) /= n) then
            call fsym_report(FSYM_ERR_SHAPE, 'q and v must have the shape given to init', &
                             stat, errmsg)
            return
        end if
        if (.not. (abs(h) > 0.0_wp .and. abs(h) <= huge(h))) then   ! zero, NaN or infinite
            call fsym_report(FSYM_ERR_BAD_STEP, 'RKN', stat, errmsg); return
        end if
        if (.not. (fsym_all_finite(d * n, q) .and. fsym_all_finite(d * n, v))) then
            call fsym_report(FSYM_ERR_NONFINITE_STATE, 'RKN, on entry', stat, errmsg); return
        end if
        istep = self%steps() + 1
        call self%counters(nf, ng, 0)
        st = FSYM_SUCCESS

        call evaluate(q, self%f0, 1)
        if (st == FSYM_SUCCESS) then
            self%qt = q + (0.5_wp * h) * v + (0.125_wp * h * h) * self%f0
            call evaluate(self%qt, self%f1, 2)
        end if
        if (st == FSYM_SUCCESS) then
            self%qt = q + h * v + (0.5_wp * h * h) * self%f1
            call evaluate(self%qt, self%f2, 3)
        end if
        call self%counters(nf, ng, 1)
        if (st == FSYM_SUCCESS) then
            ! new q into qt first, so that q is untouched if the result is not finite
            self%qt = q + h * v + (h * h / 6.0_wp) * (self%f0 + 2.0_wp * self%f1)
            self%f2 = v + (h / 6.0_wp) * (self%f0 + 4.0_wp * self%f1 + self%f2)
            if (.not. (fsym_all_finite(d * n, self%qt) .and. &
                       fsym_all_finite(d * n, self%f2))) st = FSYM_ERR_NONFINITE_STATE
        end if
        if (st /= FSYM_SUCCESS) then
            call fsym_report(st, 'RKN, step; state restored', stat, errmsg); return
        end if
        q = self%qt
        v = self%f2
        call self%count_step(h)
        if (present(stat)) stat = FSYM_SUCCESS

    contains

        subroutine evaluate(x, f, stage)
            real(wp), intent(in), contiguous :: x(:, :)
            real(wp), intent(out), contiguous :: f(:, :)
            integer, intent(in) :: stage
            mst = 0
            call model%acceleration(x, f, mst)
            nf = nf + 1
            if (present(recorder)) call recorder%record(istep, stage, EVAL_FORCE, x)
            if (mst /= 0) then
                st = FSYM_ERR_MODEL
            else if (.not. fsym_all_finite(d * n, f)) then
                st = FSYM_ERR_NONFINITE_FORCE
            end if
        end subroutine evaluate

    end subroutine rkn_step

    !> Release the workspace.
    subroutine rkn_destroy(self)
        class(rkn_t), intent(inout) :: self  !! the stepper
        call rkn_release(self)
        self%ready = .false.
    end subroutine rkn_destroy

    !> Release whatever part of the workspace is allocated.
    subroutine rkn_release(self)
        class(rkn_t), intent(inout) :: self  !! the stepper
        if (allocated(self%f0)) deallocate (self%f0)
        if (allocated(self%f1)) deallocate (self%f1)
        if (allocated(self%f2)) deallocate (self%f2)
        if (allocated(self%qt)) deallocate (self%qt)
    end subroutine rkn_release

end module fsym_rkn
