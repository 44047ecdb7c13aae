!> What the F77-callable entry points of `fsym_legacy.f90` share: the layout of the flat work
!> arrays (the only place the kernel's typed state is kept in flat arrays), the lengths a
!> method needs, the check that a work array was set up for the caller's dimensions, and
!> the force model through which the F77 face drives the one kernel with the caller's
!> EXTERNAL routines (reverse communication asks the kernel to suspend instead).
!>
!>     IW(1)  magic (initialised)        RW(1:18) the kernel state, packed by the kernel
!>     IW(2)  ND   IW(3) N                        (RW(1) h of the step in progress, RW(2)
!>     IW(4)  NOP  IW(5) NSLOT                    shift, RW(3) force and RW(4) gradient
!>     IW(6)  method id                           evaluations)
!>     IW(7)  steps completed by the last FSYMST call
!>     IW(8:) the op codes (NOP)         RW(19:) C(NOP), U(NOP), then the slots W(ND,N,NSLOT)
module fsym_legacy_work
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_UNKNOWN_METHOD, FSYM_ERR_SHAPE, &
                           FSYM_ERR_WORK_SIZE, FSYM_ERR_NOT_INITIALIZED
    use fsym_kinds, only: wp, ik
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name, fsym_catalogue, FSYM_NAME_LEN
    use fsym_force, only: force_model_t
    use fsym_kernel, only: kernel_state_t, fsym_kernel_layout, fsym_kernel_slots, &
                           fsym_kernel_pack, fsym_kernel_unpack, KERNEL_NPACK
    use fsym_legacy_api, only: fsym_legacy_accel, fsym_legacy_grad
    implicit none
    private

    integer, parameter, public :: LEGACY_MAGIC = 20260  !! IW(1) of a set-up work array
    integer, parameter, public :: LEGACY_KO = 8         !! IW index of the op codes
    integer, parameter, public :: LEGACY_KC = KERNEL_NPACK + 1  !! RW index of the coefficients

    !> The caller's EXTERNAL acceleration (and gradient) routines as a force model.
    type, extends(force_model_t), public :: legacy_model_t
        procedure(fsym_legacy_accel), pointer, nopass :: accel => null()  !! ACCEL
        procedure(fsym_legacy_grad), pointer, nopass :: grad => null()    !! GRAD
    contains
        procedure :: acceleration => legacy_acceleration  !! calls ACCEL
        procedure :: gradient => legacy_gradient          !! calls GRAD
        procedure :: has_gradient => legacy_has_gradient  !! GRAD given
    end type legacy_model_t

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
        r = LEGACY_KC - 1 + 2 * s%nop + int(nd, ik) * int(n, ik) * fsym_kernel_slots(ks)
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
        call legacy_store(ks, rw(1:KERNEL_NPACK))
        iw(1) = LEGACY_MAGIC
        iw(2) = nd; iw(3) = n; iw(4) = s%nop; iw(5) = fsym_kernel_slots(ks); iw(6) = meth
        iw(7) = 0
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

    !> The kernel state of the work arrays: laid out from IW (the op codes, ND, N) and taken
    !> over from its packed image RW(1:KERNEL_NPACK). `info`: FSYM_ERR_NOT_INITIALIZED when the
    !> image does not fit the layout or holds a flag or count out of range (RW overwritten).
    pure subroutine legacy_load(liw, iw, rw, ks, info)
        integer, intent(in) :: liw                    !! length of IW (checked by legacy_check)
        integer, intent(in) :: iw(liw)                !! IW
        real(wp), intent(in) :: rw(KERNEL_NPACK)      !! RW(1:KERNEL_NPACK)
        type(kernel_state_t), intent(out) :: ks       !! the state
        integer, intent(out) :: info                  !! status
        character(len=80) :: msg
        call fsym_kernel_layout(iw(LEGACY_KO:LEGACY_KO + iw(4) - 1), .false., iw(2), iw(3), ks)
        call fsym_kernel_unpack(rw, ks, info, msg)
        if (info /= FSYM_SUCCESS) info = FSYM_ERR_NOT_INITIALIZED
    end subroutine legacy_load

    !> Store the kernel state into RW(1:KERNEL_NPACK).
    pure subroutine legacy_store(ks, rw)
        type(kernel_state_t), intent(in) :: ks        !! the state
        real(wp), intent(out) :: rw(KERNEL_NPACK)     !! RW(1:KERNEL_NPACK)
        call fsym_kernel_pack(ks, rw)
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

end module fsym_legacy_work
