!> Agreement of the ranks of a distributed integration (issue 23): every rank runs its own
!> `integrator_t` on its block of bodies with a collective force model (`mpi_nbody_model_t`),
!> and `mpi_integrator_t` makes every refusal or failure on any rank the same status on every
!> rank, so that no rank ever waits in a collective the others have left.
!>
!> - `init`: every rank sets up its integrator, then one `MPI_Allreduce` compares the
!>   outcome, the method (a hash of its coefficient table) and the bits of the step size h:
!>   a rank that failed, or ranks that differ in method or h, give every rank the same error.
!> - `step` / `run`: before the first step of a call, one `MPI_Allreduce` of every rank's
!>   entry check (state finite, arrays of the integrator's shape, not busy): a refusal on any
!>   rank is the refusal of every rank, before any collective of the model (a rank whose own
!>   state holds a NaN no longer leaves the others waiting in the model's gather). After each
!>   step one `MPI_Allreduce` of its outcome: a failure inside the step is already common when
!>   it comes from the model (its collectives reduce the status), but the kernel can fail on
!>   one rank alone (the step's new state not finite there); then every rank whose step
!>   succeeded takes it back (`undo_step`, bitwise), and all return the same status with the
!>   state of the last step that every rank completed.
!>
!> The status is reduced as `code * 2**16 + rank` (MPI_MAX): the largest code wins, and the
!> message names the rank that reported it. Costs: two `MPI_Allreduce` of one integer per
!> `step` call, one per step plus one per `run` call, against the model's two collectives per
!> force evaluation.
module fsym_mpi_agree
    use mpi_f08, only: MPI_Comm, MPI_Comm_dup, MPI_Comm_free, MPI_Comm_rank, MPI_Allreduce, &
                       MPI_INTEGER8, MPI_MAX, MPI_SUCCESS, MPI_COMM_NULL, operator(/=), &
                       operator(==)
    use, intrinsic :: iso_fortran_env, only: int64
    use fsym_kernel, only: fsym_all_finite
    use fsym_kinds, only: wp, ik
    use fsym_status, only: fsym_report, fsym_status_message, fsym_int_text, FSYM_SUCCESS, &
                           FSYM_ERR_BAD_STEP, FSYM_ERR_BAD_ARGUMENT, FSYM_ERR_NONFINITE_STATE, &
                           FSYM_ERR_SHAPE, FSYM_ERR_NOT_INITIALIZED, FSYM_ERR_BUSY, &
                           FSYM_ERR_MODEL, FSYM_ERR_UNKNOWN_METHOD
    use fsym_force, only: force_model_t
    use fsym_integrator, only: integrator_t
    use fsym_scheme, only: scheme_t
    implicit none
    private

    integer(int64), parameter :: RANKS = 65536_int64   ! code * RANKS + rank
    integer(int64), parameter :: M31 = 2147483647_int64   ! 2**31 - 1

    !> One rank's integrator of a distributed run, in agreement with the other ranks.
    type, public :: mpi_integrator_t
        type(integrator_t) :: it                !! this rank's integrator
        type(MPI_Comm) :: comm = MPI_COMM_NULL  !! private duplicate of the communicator
        integer :: rank = 0                     !! this rank
        real(wp) :: h = 0.0_wp                  !! the common step size
        integer(int64) :: reductions = 0        !! agreement reductions so far
    contains
        procedure :: init => agree_init         !! collective set-up, method and h compared
        procedure :: step => agree_step         !! one step, the same status on every rank
        procedure :: run => agree_run           !! nsteps steps, the same status everywhere
        procedure :: destroy => agree_destroy   !! free the communicator and the workspace
    end type mpi_integrator_t

contains

    !> Collective: set up this rank's integrator for the method `name` on arrays (d, n_local)
    !> with step size `h` (the same on every rank: checked). Any rank's failure, or ranks
    !> that differ in method or h, is every rank's error (`FSYM_ERR_UNKNOWN_METHOD`...,
    !> FSYM_ERR_BAD_ARGUMENT for a method that differs, FSYM_ERR_BAD_STEP for h).
    subroutine agree_init(self, comm, name, model, d, n, h, stat, errmsg)
        class(mpi_integrator_t), intent(inout) :: self        !! the integrator
        type(MPI_Comm), intent(in) :: comm                    !! communicator of the ranks
        character(len=*), intent(in) :: name                  !! method label
        class(force_model_t), intent(in) :: model             !! force model
        integer, intent(in) :: d, n                           !! dimensions, local bodies
        real(wp), intent(in) :: h                             !! step size
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(int64) :: mine(5), all(5), hb, mh
        integer :: st, ierr
        character(len=256) :: msg
        call agree_destroy(self)
        call MPI_Comm_dup(comm, self%comm, ierr)
        call MPI_Comm_rank(self%comm, self%rank, ierr)
        msg = ''
        call self%it%init_by_name(name, model, d, n, st, msg)
        if (st == FSYM_SUCCESS .and. .not. (h /= 0.0_wp .and. abs(h) <= huge(h))) then
            st = FSYM_ERR_BAD_STEP
        end if
        hb = 0; mh = 0
        if (st == FSYM_SUCCESS) then
            hb = transfer(h, hb); mh = method_hash(self%it%scheme())
        end if
        mine = [st * RANKS + self%rank, hb, -hb, mh, -mh]
        call MPI_Allreduce(mine, all, 5, MPI_INTEGER8, MPI_MAX, self%comm, ierr)
        self%reductions = self%reductions + 1
        if (ierr /= MPI_SUCCESS) all(1) = FSYM_ERR_MODEL * RANKS + self%rank
        if (all(1) >= RANKS) then
            call fail(int(all(1) / RANKS), int(mod(all(1), RANKS)), st, msg, 'init')
        else if (all(4) /= -all(5)) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'mpi: the ranks were given different '// &
                             'methods', stat, errmsg)
        else if (all(2) /= -all(3)) then
            call fsym_report(FSYM_ERR_BAD_STEP, 'mpi: the ranks were given different step '// &
                             'sizes h', stat, errmsg)
        else
            self%h = h
            if (present(stat)) stat = FSYM_SUCCESS
            return
        end if
        call self%it%destroy()
    contains
        subroutine fail(code, r, st, msg, what)
            integer, intent(in) :: code, r, st
            character(len=*), intent(in) :: msg, what
            if (r == self%rank .and. st /= FSYM_SUCCESS .and. len_trim(msg) > 0) then
                call fsym_report(code, 'mpi '//what//', rank '//fsym_int_text(r)//': '// &
                                 trim(msg), stat, errmsg)
            else
                call fsym_report(code, 'mpi '//what//': rank '//fsym_int_text(r)//' failed ('// &
                                 fsym_status_message(code)//')', stat, errmsg)
            end if
        end subroutine fail
    end subroutine agree_init

    !> Collective: one step of the common size h. The same status on every rank; on failure
    !> every rank's q, v are those before the step.
    subroutine agree_step(self, model, q, v, stat, errmsg)
        class(mpi_integrator_t), intent(inout) :: self        !! the integrator
        class(force_model_t), intent(inout) :: model          !! the collective force model
        real(wp), intent(inout), contiguous :: q(:, :)        !! own positions (d, n_local)
        real(wp), intent(inout), contiguous :: v(:, :)        !! own velocities
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        call agree_run(self, model, q, v, 1_ik, stat, errmsg)
    end subroutine agree_step

    !> Collective: `nsteps` steps of the common size h, each agreed by all ranks; stops at the
    !> first step that fails on any rank, with the same status on every rank and the state of
    !> the last step every rank completed.
    subroutine agree_run(self, model, q, v, nsteps, stat, errmsg)
        class(mpi_integrator_t), intent(inout) :: self        !! the integrator
        class(force_model_t), intent(inout) :: model          !! the collective force model
        real(wp), intent(inout), contiguous :: q(:, :)        !! own positions (d, n_local)
        real(wp), intent(inout), contiguous :: v(:, :)        !! own velocities
        integer(ik), intent(in) :: nsteps                     !! number of steps
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(ik) :: i
        integer :: st, code, r, d, n
        character(len=256) :: msg
        msg = ''
        ! the entry check of every rank, agreed before any collective of the model
        call self%it%dims(d, n)
        st = FSYM_SUCCESS
        if (self%comm == MPI_COMM_NULL .or. self%it%checkpoint_length() == 0) then
            st = FSYM_ERR_NOT_INITIALIZED
        else if (self%it%in_use()) then
            st = FSYM_ERR_BUSY
        else if (size(q, 1) /= d .or. size(q, 2) /= n .or. any(shape(v) /= shape(q))) then
            st = FSYM_ERR_SHAPE
        else if (.not. (fsym_all_finite(size(q), q) .and. fsym_all_finite(size(v), v))) then
            st = FSYM_ERR_NONFINITE_STATE
        else if (nsteps < 1) then
            st = FSYM_ERR_BAD_ARGUMENT
        end if
        if (self%comm == MPI_COMM_NULL) then     ! no communicator: nothing to agree with
            call fsym_report(st, 'mpi step before init', stat, errmsg); return
        end if
        call agree(self, st, code, r)
        if (code /= FSYM_SUCCESS) then
            call report(code, r, st, 'refused on entry (nothing changed on any rank)'); return
        end if
        do i = 1, nsteps
            msg = ''
            call self%it%step(model, q, v, self%h, st, msg)
            call agree(self, st, code, r)
            if (code /= FSYM_SUCCESS) then
                if (st == FSYM_SUCCESS) call self%it%undo_step(q, v)
                call report(code, r, st, 'step '//fsym_int_text(self%it%steps() + 1)// &
                            ' undone on every rank')
                return
            end if
        end do
        if (present(stat)) stat = FSYM_SUCCESS
    contains
        subroutine report(code, r, st, what)
            integer, intent(in) :: code, r, st
            character(len=*), intent(in) :: what
            if (r == self%rank .and. st /= FSYM_SUCCESS .and. len_trim(msg) > 0) then
                call fsym_report(code, 'mpi rank '//fsym_int_text(r)//': '//trim(msg)// &
                                 '; '//what, stat, errmsg)
            else
                call fsym_report(code, 'mpi: rank '//fsym_int_text(r)//' reported '// &
                                 fsym_status_message(code)//'; '//what, stat, errmsg)
            end if
        end subroutine report
    end subroutine agree_run

    !> The common status: one MPI_Allreduce (max) of code * 2**16 + rank.
    subroutine agree(self, st, code, r)
        class(mpi_integrator_t), intent(inout) :: self
        integer, intent(in) :: st          ! this rank's status
        integer, intent(out) :: code, r    ! the largest status and the rank that reported it
        integer(int64) :: mine, all
        integer :: ierr
        mine = int(st, int64) * RANKS + self%rank
        call MPI_Allreduce(mine, all, 1, MPI_INTEGER8, MPI_MAX, self%comm, ierr)
        self%reductions = self%reductions + 1
        if (ierr /= MPI_SUCCESS) all = FSYM_ERR_MODEL * RANKS + self%rank
        code = int(all / RANKS); r = int(mod(all, RANKS))
    end subroutine agree

    !> Free the communicator and the integrator's workspace (before MPI_Finalize).
    subroutine agree_destroy(self)
        class(mpi_integrator_t), intent(inout) :: self  !! the integrator
        integer :: ierr
        if (self%comm /= MPI_COMM_NULL) call MPI_Comm_free(self%comm, ierr)
        call self%it%destroy()
    end subroutine agree_destroy

    !> A hash of a method's table (op codes and the bits of c and u), to compare ranks.
    pure integer(int64) function method_hash(s) result(hsh)
        type(scheme_t), intent(in) :: s
        integer :: k
        hsh = 7
        do k = 1, s%nop
            hsh = mix(hsh, int(s%op(k), int64))
            hsh = mix_real(hsh, s%c(k))
            hsh = mix_real(hsh, s%u(k))
        end do
    contains
        !> the 64 bits of x in three parts
        pure integer(int64) function mix_real(a, x)
            integer(int64), intent(in) :: a
            real(wp), intent(in) :: x
            integer(int64) :: b
            b = transfer(x, b)
            mix_real = mix(mix(mix(a, iand(b, M31)), iand(shiftr(b, 31), M31)), shiftr(b, 62))
        end function mix_real
        !> a polynomial hash modulo the prime 2**31 - 1 (no product exceeds 2**62)
        pure integer(int64) function mix(a, b)
            integer(int64), intent(in) :: a, b
            mix = mod(a * 1000003_int64 + b, M31)
        end function mix
    end function method_hash

end module fsym_mpi_agree
