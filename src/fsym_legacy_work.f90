!> What the F77-callable entry points of `fsym_legacy.f90` share: the layout of the flat work
!> arrays (the only place the kernel's typed state is kept in flat arrays), the lengths a
!> method needs, the check that a work array was set up for the caller's dimensions, and
!> the two small force models through which the F77 face drives the one kernel: one calls
!> the caller's EXTERNAL routines, the other suspends the kernel for reverse communication.
!>
!>     IW(1)  magic (initialised)        RW(1) h of the step in progress
!>     IW(2)  ND   IW(3) N               RW(2) shift of the cached extrapolated force
!>     IW(4)  NOP  IW(5) NSLOT           RW(3) force evaluations, RW(4) gradient evaluations
!>     IW(6)  method id                  RW(5:) C(NOP), U(NOP), then the slots W(ND,N,NSLOT)
!>     IW(7)  steps completed by the last FSYMST call
!>     IW(8:) the kernel state (LEGACY_NKI integers), then the op codes (NOP)
module fsym_legacy_work
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_UNKNOWN_METHOD, FSYM_ERR_SHAPE, &
                           FSYM_ERR_WORK_SIZE, FSYM_ERR_NOT_INITIALIZED
    use fsym_kinds, only: wp, ik
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name, fsym_catalogue, FSYM_NAME_LEN
    use fsym_force, only: force_model_t
    use fsym_kernel, only: kernel_state_t, fsym_kernel_layout, KERNEL_SUSPEND
    use fsym_legacy_api, only: fsym_legacy_accel, fsym_legacy_grad
    implicit none
    private

    integer, parameter, public :: LEGACY_MAGIC = 20260  !! IW(1) of a set-up work array
    integer, parameter, public :: LEGACY_NKI = 21       !! integers of the kernel state
    integer, parameter, public :: LEGACY_KO = 8 + LEGACY_NKI  !! IW index of the op codes
    integer, parameter, public :: LEGACY_KC = 5         !! RW index of the coefficients

    !> The caller's EXTERNAL acceleration (and gradient) routines as a force model.
    type, extends(force_model_t), public :: legacy_model_t
        procedure(fsym_legacy_accel), pointer, nopass :: accel => null()  !! ACCEL
        procedure(fsym_legacy_grad), pointer, nopass :: grad => null()    !! GRAD
    contains
        procedure :: acceleration => legacy_acceleration  !! calls ACCEL
        procedure :: gradient => legacy_gradient          !! calls GRAD
        procedure :: has_gradient => legacy_has_gradient  !! GRAD given
    end type legacy_model_t

    !> Reverse communication: every evaluation suspends the kernel; the caller supplies it.
    type, extends(force_model_t), public :: suspend_model_t
    contains
        procedure :: acceleration => suspend_acceleration  !! suspends
        procedure :: gradient => suspend_gradient          !! suspends
        procedure :: has_gradient => suspend_has_gradient  !! true
    end type suspend_model_t

    public :: legacy_sizes, legacy_scheme_sizes, legacy_setup, legacy_ok, legacy_check
    public :: legacy_load, legacy_store

contains

    !> Lengths of the real and integer work arrays of catalogue method `meth` on (nd, n).
    !> Computed in 64-bit integers: lengths that do not fit a default integer are an error
    !> (FSYM_ERR_WORK_SIZE, lrw = liw = 0), never a wrapped-around number.
    subroutine legacy_sizes(meth, nd, n, lrw, liw, info)
        integer, intent(in) :: meth      !! catalogue index
        integer, intent(in) :: nd, n     !! dimensions, bodies
        integer, intent(out) :: lrw      !! reals needed
        integer, intent(out) :: liw      !! integers needed
        integer, intent(out) :: info     !! status
        type(scheme_t) :: s
        character(len=FSYM_NAME_LEN), allocatable :: cat(:)
        lrw = 0; liw = 0
        cat = fsym_catalogue()
        if (meth < 1 .or. meth > size(cat)) then
            info = FSYM_ERR_UNKNOWN_METHOD; return
        end if
        call fsym_scheme_by_name(cat(meth), s, info)
        if (info /= FSYM_SUCCESS) return
        call legacy_scheme_sizes(s, nd, n, lrw, liw, info)
    end subroutine legacy_sizes

    !> Lengths of the work arrays of scheme `s` on (nd, n), in 64-bit arithmetic; lengths
    !> beyond a default integer give FSYM_ERR_WORK_SIZE and lrw = liw = 0.
    subroutine legacy_scheme_sizes(s, nd, n, lrw, liw, info)
        type(scheme_t), intent(in) :: s  !! the scheme
        integer, intent(in) :: nd, n     !! dimensions, bodies
        integer, intent(out) :: lrw      !! reals needed
        integer, intent(out) :: liw      !! integers needed
        integer, intent(out) :: info     !! status
        type(kernel_state_t) :: ks
        integer(ik) :: r
        lrw = 0; liw = 0
        if (nd < 1 .or. n < 1) then
            info = FSYM_ERR_SHAPE; return
        end if
        call fsym_kernel_layout(s%op, .false., nd, n, ks)
        r = LEGACY_KC - 1 + 2 * s%nop + int(nd, ik) * int(n, ik) * ks%nslot
        if (r > huge(lrw)) then
            info = FSYM_ERR_WORK_SIZE; return
        end if
        lrw = int(r)
        liw = LEGACY_KO - 1 + s%nop
        info = FSYM_SUCCESS
    end subroutine legacy_scheme_sizes

    !> Fill the work arrays for scheme `s` (catalogue index `meth`, 0 for a label outside
    !> the catalogue) on (nd, n). Short arrays are rejected and nothing is written.
    subroutine legacy_setup(s, meth, nd, n, rw, lrw, iw, liw, info)
        type(scheme_t), intent(in) :: s          !! the scheme
        integer, intent(in) :: meth              !! catalogue index or 0
        integer, intent(in) :: nd, n             !! dimensions, bodies
        integer, intent(in) :: lrw, liw          !! lengths of rw and iw
        real(wp), intent(inout) :: rw(lrw)       !! real work array
        integer, intent(inout) :: iw(liw)        !! integer work array
        integer, intent(out) :: info             !! status
        type(kernel_state_t) :: ks
        integer :: need_r, need_i
        call legacy_scheme_sizes(s, nd, n, need_r, need_i, info)
        if (info /= FSYM_SUCCESS) return
        if (lrw < need_r .or. liw < need_i) then
            info = FSYM_ERR_WORK_SIZE; return
        end if
        iw(1:need_i) = 0
        rw(1:need_r) = 0.0_wp
        call fsym_kernel_layout(s%op, .false., nd, n, ks)
        call legacy_store(ks, iw(8:LEGACY_KO - 1), rw(1:4))
        iw(1) = LEGACY_MAGIC
        iw(2) = nd; iw(3) = n; iw(4) = s%nop; iw(5) = ks%nslot; iw(6) = meth; iw(7) = 0
        iw(LEGACY_KO:LEGACY_KO + s%nop - 1) = s%op
        rw(LEGACY_KC:LEGACY_KC + s%nop - 1) = s%c
        rw(LEGACY_KC + s%nop:LEGACY_KC + 2 * s%nop - 1) = s%u
        info = FSYM_SUCCESS
    end subroutine legacy_setup

    !> True when `iw` was set up by FSYMIN for (nd, n) and the lengths suffice.
    pure logical function legacy_ok(nd, n, lrw, liw, iw)
        integer, intent(in) :: nd, n, lrw, liw   !! dimensions and lengths given by the caller
        integer, intent(in) :: iw(liw)           !! integer work array
        legacy_ok = legacy_check(nd, n, lrw, liw, iw) == FSYM_SUCCESS
    end function legacy_ok

    !> Why the work arrays cannot be used for (nd, n): FSYM_ERR_NOT_INITIALIZED when `iw`
    !> was not set up by FSYMIN (or is too short to tell), FSYM_ERR_SHAPE when it was set up
    !> for other dimensions, FSYM_ERR_WORK_SIZE when LRW or LIW is shorter than it needs;
    !> FSYM_SUCCESS when they are fine. Lengths are compared in 64-bit arithmetic.
    pure integer function legacy_check(nd, n, lrw, liw, iw) result(info)
        integer, intent(in) :: nd, n, lrw, liw   !! dimensions and lengths given by the caller
        integer, intent(in) :: iw(liw)           !! integer work array
        info = FSYM_ERR_NOT_INITIALIZED
        if (liw < 7) return
        if (iw(1) /= LEGACY_MAGIC .or. iw(4) < 1 .or. iw(5) < 1) return
        info = FSYM_ERR_SHAPE
        if (iw(2) /= nd .or. iw(3) /= n) return
        info = FSYM_ERR_WORK_SIZE
        if (liw < LEGACY_KO - 1 + iw(4)) return
        if (int(lrw, ik) < LEGACY_KC - 1 + 2 * iw(4) + int(nd, ik) * int(n, ik) * iw(5)) return
        info = FSYM_SUCCESS
    end function legacy_check

    !> The kernel state kept in IW(8:) and RW(1:4).
    pure subroutine legacy_load(iw, rw, ks)
        integer, intent(in) :: iw(LEGACY_NKI)     !! IW(8:)
        real(wp), intent(in) :: rw(4)             !! RW(1:4)
        type(kernel_state_t), intent(out) :: ks   !! the state
        ks%d = iw(1); ks%n = iw(2); ks%nslot = iw(3)
        ks%ia = iw(4); ks%ig = iw(5); ks%iqe = iw(6); ks%iae = iw(7)
        ks%iq0 = iw(8); ks%iv0 = iw(9); ks%iqlast = iw(10)
        ks%iqc = iw(11); ks%ivc = iw(12); ks%iqc0 = iw(13); ks%ivc0 = iw(14)
        ks%comp = iw(15) /= 0; ks%have_a = iw(16) /= 0; ks%have_g = iw(17) /= 0
        ks%have_x = iw(18) /= 0; ks%active = btest(iw(19), 0)
        ks%qsaved = btest(iw(19), 1); ks%vsaved = btest(iw(19), 2)
        ks%pc = iw(20); ks%req = iw(21)
        ks%h = rw(1); ks%xshift = rw(2)
        ks%nf = int(rw(3), ik); ks%ng = int(rw(4), ik)
    end subroutine legacy_load

    !> Store the kernel state into IW(8:) and RW(1:4).
    pure subroutine legacy_store(ks, iw, rw)
        type(kernel_state_t), intent(in) :: ks    !! the state
        integer, intent(out) :: iw(LEGACY_NKI)    !! IW(8:)
        real(wp), intent(out) :: rw(4)            !! RW(1:4)
        iw = [ks%d, ks%n, ks%nslot, ks%ia, ks%ig, ks%iqe, ks%iae, ks%iq0, ks%iv0, ks%iqlast, &
              ks%iqc, ks%ivc, ks%iqc0, ks%ivc0, merge(1, 0, ks%comp), merge(1, 0, ks%have_a), &
              merge(1, 0, ks%have_g), merge(1, 0, ks%have_x), &
              merge(1, 0, ks%active) + merge(2, 0, ks%qsaved) + merge(4, 0, ks%vsaved), ks%pc, &
              ks%req]
        rw = [ks%h, ks%xshift, real(ks%nf, wp), real(ks%ng, wp)]
    end subroutine legacy_store

    subroutine legacy_acceleration(self, q, a, stat)
        class(legacy_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)   !! positions (d, n)
        real(wp), intent(out), contiguous :: a(:, :)  !! accelerations (d, n)
        integer, intent(inout) :: stat                !! unchanged (ACCEL has no status)
        call self%accel(size(q, 1), size(q, 2), q, a)
    end subroutine legacy_acceleration

    subroutine legacy_gradient(self, q, a, g, stat)
        class(legacy_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)   !! positions (d, n)
        real(wp), intent(in), contiguous :: a(:, :)   !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)  !! gradient term (d, n)
        integer, intent(inout) :: stat                !! unchanged (GRAD has no status)
        call self%grad(size(q, 1), size(q, 2), q, a, g)
    end subroutine legacy_gradient

    logical function legacy_has_gradient(self)
        class(legacy_model_t), intent(in) :: self  !! the model
        legacy_has_gradient = associated(self%grad)
    end function legacy_has_gradient

    subroutine suspend_acceleration(self, q, a, stat)
        class(suspend_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)    !! positions (d, n)
        real(wp), intent(out), contiguous :: a(:, :)   !! not written: the caller fills it
        integer, intent(inout) :: stat                 !! KERNEL_SUSPEND
        stat = KERNEL_SUSPEND
    end subroutine suspend_acceleration

    subroutine suspend_gradient(self, q, a, g, stat)
        class(suspend_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)    !! positions (d, n)
        real(wp), intent(in), contiguous :: a(:, :)    !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)   !! not written: the caller fills it
        integer, intent(inout) :: stat                 !! KERNEL_SUSPEND
        stat = KERNEL_SUSPEND
    end subroutine suspend_gradient

    logical function suspend_has_gradient(self)
        class(suspend_model_t), intent(in) :: self  !! the model
        suspend_has_gradient = .true.
    end function suspend_has_gradient

end module fsym_legacy_work
