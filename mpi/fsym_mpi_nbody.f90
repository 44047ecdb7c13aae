!> Distributed direct-summation N-body model over MPI (optional target `fsym_mpi`; the core
!> library stays MPI-free).
!>
!> Each rank owns a contiguous block of bodies (any sizes >= 1, given or an even split) and
!> integrates only that block with the library's `integrator_t`: its positions and
!> velocities are arrays (3, n_local). `mpi_nbody_model_t` extends `force_model_t`:
!>
!> - `acceleration`: one `MPI_Allgatherv` of the positions (3 reals per body) into a copy of
!>   all positions, then the accelerations of the own block from the library's pair kernel
!>   (`fsym_nbody_accel_range`, the routine the serial and threaded models call), then one
!>   `MPI_Allreduce` (max) of the status;
!> - `gradient` (methods A, C, AN): one `MPI_Allgatherv` of the accelerations (3 reals per
!>   body and one flag per rank that says whether the positions changed since they were last
!>   gathered; if any did, the positions are gathered again), then
!>   `fsym_nbody_gradient_range` for the own block, then the status reduction.
!>
!> Every body's sum therefore runs over all bodies in the library's order (see `fsym_nbody`)
!> on whichever rank owns it, exactly as in the serial model: the results are bitwise those
!> of the serial run for any number of ranks, any block sizes and any number of threads per
!> rank.
!>
!> Failure: a rank whose force fails (its own status from `local_acceleration` or
!> `local_gradient`, a bad shape, or a non-finite result) makes the status reduction non-zero
!> on every rank, so every rank's force returns a failure and every rank's integrator undoes
!> the step: the state stays intact on all ranks and the ranks stay in step (no rank waits in
!> a collective the others have left). Collectives are on a duplicate of the communicator
!> given to `init`; call `destroy` before `MPI_Finalize`.
module fsym_mpi_nbody
    use mpi_f08, only: MPI_Comm, MPI_Comm_dup, MPI_Comm_free, MPI_Comm_rank, MPI_Comm_size, &
                       MPI_Allgatherv, MPI_Allreduce, MPI_IN_PLACE, MPI_DOUBLE_PRECISION, &
                       MPI_INTEGER, MPI_MAX, MPI_SUCCESS, MPI_COMM_NULL, operator(/=)
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fsym_kinds, only: wp
    use fsym_status, only: fsym_report, FSYM_SUCCESS, FSYM_ERR_SHAPE, FSYM_ERR_BAD_ARGUMENT, &
                           FSYM_ERR_NOT_INITIALIZED, FSYM_ERR_NONFINITE_FORCE, FSYM_ERR_MODEL
    use fsym_force, only: force_model_t
    use fsym_nbody, only: fsym_nbody_accel_range, fsym_nbody_gradient_range
    implicit none
    private

    !> Gravity of n bodies distributed over the ranks of a communicator, in blocks.
    type, extends(force_model_t), public :: mpi_nbody_model_t
        type(MPI_Comm) :: comm = MPI_COMM_NULL  !! private duplicate of the user's communicator
        integer :: rank = 0                     !! this rank
        integer :: nranks = 0                   !! number of ranks
        integer :: n = 0                        !! bodies in total
        integer :: first = 0                    !! first body of this rank's block
        integer :: last = -1                    !! last body of this rank's block
        real(wp), allocatable :: m(:)           !! masses of all bodies
        real(wp) :: g = 1.0_wp                  !! gravitational constant
        real(wp) :: eps = 0.0_wp                !! Plummer softening length
        integer, allocatable :: counts(:)       !! bodies per rank
        integer, allocatable :: qcounts(:)      !! reals per rank in the position gather
        integer, allocatable :: qdispls(:)      !! offsets in the position gather
        integer, allocatable :: gcounts(:)      !! reals per rank in the acceleration gather
        integer, allocatable :: gdispls(:)      !! offsets in the acceleration gather
        real(wp), allocatable :: qall(:, :)     !! positions of all bodies, last gathered
        real(wp), allocatable :: aall(:, :)     !! accelerations of all bodies (gradient)
        real(wp), allocatable :: gbuf(:)        !! buffer of the acceleration gather
        integer(int64) :: gathers = 0           !! MPI_Allgatherv calls so far
        integer(int64) :: reductions = 0        !! MPI_Allreduce calls so far
    contains
        procedure :: init => mpi_nbody_init
        procedure :: destroy => mpi_nbody_destroy
        procedure :: acceleration => mpi_nbody_acceleration
        procedure :: gradient => mpi_nbody_gradient
        procedure :: has_gradient => mpi_nbody_has_gradient
        procedure :: local_acceleration => mpi_nbody_local_acceleration
        procedure :: local_gradient => mpi_nbody_local_gradient
        procedure :: local_size => mpi_nbody_local_size
    end type mpi_nbody_model_t

contains

    !> Set up on communicator `comm` (collective: every rank calls it with the same masses,
    !> G, softening and counts). `counts(r+1)` is the number of bodies of rank r (each >= 1,
    !> summing to size(m)); without it the bodies are split evenly, the first mod(n, ranks)
    !> ranks taking one more. On error nothing is changed, and every rank gets the error.
    subroutine mpi_nbody_init(self, comm, m, g, eps, counts, stat, errmsg)
        class(mpi_nbody_model_t), intent(inout) :: self       !! the model
        type(MPI_Comm), intent(in) :: comm                    !! communicator of the ranks
        real(wp), intent(in) :: m(:)                          !! masses of all bodies
        real(wp), intent(in) :: g                             !! gravitational constant
        real(wp), intent(in), optional :: eps                 !! softening length (default 0)
        integer, intent(in), optional :: counts(:)            !! bodies per rank
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer :: rank, nranks, ierr, n, r, e_local, e_all
        integer, allocatable :: c(:)
        real(wp) :: e
        e = 0.0_wp
        if (present(eps)) e = eps
        n = size(m)
        call MPI_Comm_rank(comm, rank, ierr)
        call MPI_Comm_size(comm, nranks, ierr)
        allocate (c(nranks))
        e_local = FSYM_SUCCESS
        if (present(counts)) then
            if (size(counts) /= nranks) then
                e_local = FSYM_ERR_SHAPE
            else
                c = counts
            end if
        else
            c = n / nranks
            c(1:mod(n, nranks)) = c(1:mod(n, nranks)) + 1
        end if
        if (e_local == FSYM_SUCCESS) then
            if (any(c < 1) .or. sum(c) /= n) e_local = FSYM_ERR_SHAPE
        end if
        if (e_local == FSYM_SUCCESS) then
            if (.not. (all(m > 0.0_wp) .and. all(m <= huge(m)) .and. g > 0.0_wp .and. &
                       g <= huge(g) .and. e >= 0.0_wp .and. e <= huge(e))) then
                e_local = FSYM_ERR_BAD_ARGUMENT
            end if
        end if
        call MPI_Allreduce(e_local, e_all, 1, MPI_INTEGER, MPI_MAX, comm, ierr)
        if (e_all /= FSYM_SUCCESS) then
            if (e_all == FSYM_ERR_SHAPE) then
                call fsym_report(e_all, 'mpi_nbody: counts must be one per rank, each >= 1, '// &
                                 'summing to the number of bodies', stat, errmsg)
            else
                call fsym_report(e_all, 'mpi_nbody: need masses > 0, G > 0 and eps >= 0, '// &
                                 'finite', stat, errmsg)
            end if
            return
        end if
        call mpi_nbody_destroy(self)
        call MPI_Comm_dup(comm, self%comm, ierr)
        self%rank = rank
        self%nranks = nranks
        self%n = n
        self%m = m
        self%g = g
        self%eps = e
        self%counts = c
        self%first = sum(c(1:rank)) + 1
        self%last = self%first + c(rank + 1) - 1
        allocate (self%qcounts(nranks), self%qdispls(nranks), self%gcounts(nranks), &
                  self%gdispls(nranks))
        do r = 1, nranks
            self%qcounts(r) = 3 * c(r)
            self%qdispls(r) = 3 * sum(c(1:r - 1))
            self%gcounts(r) = 3 * c(r) + 1
            self%gdispls(r) = 3 * sum(c(1:r - 1)) + (r - 1)
        end do
        allocate (self%qall(3, n), self%aall(3, n), self%gbuf(3 * n + nranks))
        self%qall = huge(1.0_wp)
        self%aall = 0.0_wp
        self%gathers = 0
        self%reductions = 0
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine mpi_nbody_init

    !> Free the communicator and the buffers (call it before `MPI_Finalize`).
    subroutine mpi_nbody_destroy(self)
        class(mpi_nbody_model_t), intent(inout) :: self  !! the model
        integer :: ierr
        if (self%comm /= MPI_COMM_NULL) call MPI_Comm_free(self%comm, ierr)
        if (allocated(self%m)) deallocate (self%m)
        if (allocated(self%counts)) deallocate (self%counts)
        if (allocated(self%qcounts)) deallocate (self%qcounts, self%qdispls, self%gcounts, &
                                                 self%gdispls)
        if (allocated(self%qall)) deallocate (self%qall, self%aall, self%gbuf)
        self%n = 0
        self%first = 0
        self%last = -1
    end subroutine mpi_nbody_destroy

    !> Number of bodies this rank owns (the n of its `integrator_t`).
    pure integer function mpi_nbody_local_size(self)
        class(mpi_nbody_model_t), intent(in) :: self  !! the model
        mpi_nbody_local_size = self%last - self%first + 1
    end function mpi_nbody_local_size

    !> Gradient term available once initialised.
    logical function mpi_nbody_has_gradient(self)
        class(mpi_nbody_model_t), intent(in) :: self  !! the model
        mpi_nbody_has_gradient = allocated(self%m)
    end function mpi_nbody_has_gradient

    !> Accelerations of the own block (collective: gather, local kernel, status reduction).
    subroutine mpi_nbody_acceleration(self, q, a, stat)
        class(mpi_nbody_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)      !! own positions (3, n_local)
        real(wp), intent(out), contiguous :: a(:, :)     !! own accelerations (3, n_local)
        integer, intent(inout) :: stat                   !! 0 on entry; the common status
        integer :: lst, ierr
        a = 0.0_wp
        if (.not. allocated(self%m)) then
            stat = FSYM_ERR_NOT_INITIALIZED; return
        end if
        lst = shape_status(self, q, a)
        if (lst == FSYM_SUCCESS) self%qall(:, self%first:self%last) = q
        call MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DOUBLE_PRECISION, self%qall, self%qcounts, &
                            self%qdispls, MPI_DOUBLE_PRECISION, self%comm, ierr)
        self%gathers = self%gathers + 1
        if (ierr /= MPI_SUCCESS .and. lst == FSYM_SUCCESS) lst = FSYM_ERR_MODEL
        if (lst == FSYM_SUCCESS) call self%local_acceleration(self%qall, a, lst)
        if (lst == FSYM_SUCCESS .and. .not. all_finite(a)) lst = FSYM_ERR_NONFINITE_FORCE
        call agree(self, lst, stat)
        if (stat /= FSYM_SUCCESS) a = 0.0_wp
    end subroutine mpi_nbody_acceleration

    !> Gradient term of the own block (collective: gather of the accelerations, of the
    !> positions again if any rank's changed since the last gather, local kernel, status).
    subroutine mpi_nbody_gradient(self, q, a, g, stat)
        class(mpi_nbody_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)      !! own positions (3, n_local)
        real(wp), intent(in), contiguous :: a(:, :)      !! own accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)     !! own gradient term (3, n_local)
        integer, intent(inout) :: stat                   !! 0 on entry; the common status
        integer :: lst, ierr, r, j, k, o
        logical :: stale
        g = 0.0_wp
        if (.not. allocated(self%m)) then
            stat = FSYM_ERR_NOT_INITIALIZED; return
        end if
        lst = shape_status(self, q, g)
        if (lst == FSYM_SUCCESS .and. any(shape(a) /= shape(q))) lst = FSYM_ERR_SHAPE
        o = self%gdispls(self%rank + 1)
        self%gbuf(o + 1:o + 3 * self%local_size() + 1) = 0.0_wp
        if (lst == FSYM_SUCCESS) then
            do j = 1, self%local_size()
                self%gbuf(o + 3 * j - 2:o + 3 * j) = a(:, j)
            end do
            if (.not. same_bits(q, self%qall(:, self%first:self%last))) then
                self%gbuf(o + 3 * self%local_size() + 1) = 1.0_wp
            end if
        end if
        call MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DOUBLE_PRECISION, self%gbuf, self%gcounts, &
                            self%gdispls, MPI_DOUBLE_PRECISION, self%comm, ierr)
        self%gathers = self%gathers + 1
        if (ierr /= MPI_SUCCESS .and. lst == FSYM_SUCCESS) lst = FSYM_ERR_MODEL
        stale = .false.
        k = 0
        do r = 1, self%nranks
            o = self%gdispls(r)
            do j = 1, self%counts(r)
                self%aall(:, k + j) = self%gbuf(o + 3 * j - 2:o + 3 * j)
            end do
            k = k + self%counts(r)
            stale = stale .or. self%gbuf(o + 3 * self%counts(r) + 1) > 0.5_wp
        end do
        if (stale) then
            ! every rank saw the same flags, so every rank takes this branch
            if (lst == FSYM_SUCCESS) self%qall(:, self%first:self%last) = q
            call MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DOUBLE_PRECISION, self%qall, &
                                self%qcounts, self%qdispls, MPI_DOUBLE_PRECISION, self%comm, ierr)
            self%gathers = self%gathers + 1
            if (ierr /= MPI_SUCCESS .and. lst == FSYM_SUCCESS) lst = FSYM_ERR_MODEL
        end if
        if (lst == FSYM_SUCCESS) call self%local_gradient(self%qall, self%aall, g, lst)
        if (lst == FSYM_SUCCESS .and. .not. all_finite(g)) lst = FSYM_ERR_NONFINITE_FORCE
        call agree(self, lst, stat)
        if (stat /= FSYM_SUCCESS) g = 0.0_wp
    end subroutine mpi_nbody_gradient

    !> The rank's own force: accelerations of bodies first..last from all positions. Extend
    !> the type and override this (not `acceleration`) to change the physics or to make a
    !> rank fail on purpose; the collective part stays the same.
    subroutine mpi_nbody_local_acceleration(self, qall, a, stat)
        class(mpi_nbody_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in) :: qall(:, :)               !! positions of all bodies (3, n)
        real(wp), intent(out) :: a(:, :)                 !! own accelerations (3, n_local)
        integer, intent(inout) :: stat                   !! set non-zero on failure
        associate (unused => stat); end associate   ! the built-in force never fails
        call fsym_nbody_accel_range(self%n, self%m, self%g, self%eps, qall, self%first, &
                                    self%last, a)
    end subroutine mpi_nbody_local_acceleration

    !> The rank's own gradient term from all positions and accelerations (override as
    !> `local_acceleration`).
    subroutine mpi_nbody_local_gradient(self, qall, aall, g, stat)
        class(mpi_nbody_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in) :: qall(:, :)               !! positions of all bodies (3, n)
        real(wp), intent(in) :: aall(:, :)               !! accelerations of all bodies
        real(wp), intent(out) :: g(:, :)                 !! own gradient term (3, n_local)
        integer, intent(inout) :: stat                   !! set non-zero on failure
        associate (unused => stat); end associate   ! the built-in force never fails
        call fsym_nbody_gradient_range(self%n, self%m, self%g, self%eps, qall, aall, &
                                       self%first, self%last, g)
    end subroutine mpi_nbody_local_gradient

    !> FSYM_SUCCESS when q and the result array are (3, n_local), else FSYM_ERR_SHAPE.
    pure integer function shape_status(self, q, a) result(st)
        class(mpi_nbody_model_t), intent(in) :: self  !! the model
        real(wp), intent(in) :: q(:, :)               !! own positions
        real(wp), intent(in) :: a(:, :)               !! own result array
        st = FSYM_SUCCESS
        if (size(q, 1) /= 3 .or. size(q, 2) /= self%local_size() .or. &
            any(shape(a) /= shape(q))) st = FSYM_ERR_SHAPE
    end function shape_status

    !> The common status: the largest local status over all ranks (one MPI_Allreduce).
    subroutine agree(self, lst, stat)
        class(mpi_nbody_model_t), intent(inout) :: self  !! the model
        integer, intent(in) :: lst                       !! this rank's status
        integer, intent(inout) :: stat                   !! set to the common status if not 0
        integer :: gst, ierr
        call MPI_Allreduce(lst, gst, 1, MPI_INTEGER, MPI_MAX, self%comm, ierr)
        self%reductions = self%reductions + 1
        if (ierr /= MPI_SUCCESS) gst = FSYM_ERR_MODEL
        if (gst /= FSYM_SUCCESS) stat = gst
    end subroutine agree

    !> Whether every element is finite.
    pure logical function all_finite(x)
        real(wp), intent(in) :: x(:, :)  !! array to check
        integer :: i, j
        all_finite = .true.
        do j = 1, size(x, 2)
            do i = 1, size(x, 1)
                if (.not. ieee_is_finite(x(i, j))) all_finite = .false.
            end do
        end do
    end function all_finite

    !> Whether x and y hold the same bits (so that +0 and -0 count as different).
    pure logical function same_bits(x, y)
        real(wp), intent(in) :: x(:, :)  !! first array
        real(wp), intent(in) :: y(:, :)  !! second array, same shape
        integer :: i, j
        same_bits = .true.
        do j = 1, size(x, 2)
            do i = 1, size(x, 1)
                if (transfer(x(i, j), 0_int64) /= transfer(y(i, j), 0_int64)) same_bits = .false.
            end do
        end do
    end function same_bits

end module fsym_mpi_nbody
