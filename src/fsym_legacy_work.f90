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
!>     then, after the op codes (K = 8 + NOP):
!>     IW(K)    busy flag (1 while FSYMST/FSYMGD call the caller's routines)
!>     IW(K+1:K+2)  the method's stability limit x* (the bits of a double), for FSYMGD
!>     IW(K+3)  CRC-32 of IW(1:K+2), IW(K+4) and the bits of C and U in RW (a changed word of
!>              IW, or a changed coefficient, is refused on entry: INFO = 9)
!>     IW(K+4)  guard word LEGACY_GUARD (an overrun of IW, or a shorter IW, is refused)
module fsym_legacy_work
    use, intrinsic :: iso_fortran_env, only: int64
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_UNKNOWN_METHOD, FSYM_ERR_SHAPE, &
                           FSYM_ERR_WORK_SIZE, FSYM_ERR_NOT_INITIALIZED, FSYM_ERR_BUSY
    use fsym_kinds, only: wp, ik
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name, fsym_catalogue, FSYM_NAME_LEN
    use fsym_force, only: force_model_t
    use fsym_kernel, only: kernel_state_t, fsym_kernel_layout, fsym_kernel_slots, &
                           fsym_kernel_pack, fsym_kernel_unpack, KERNEL_NPACK
    use fsym_legacy_api, only: fsym_legacy_accel, fsym_legacy_grad, fsym_legacy_freq
    use fsym_kernel, only: fsym_kernel_run, fsym_kernel_request, REQ_NONE
    use fsym_guard, only: guard_t, fsym_guard_run
    use fsym_integrator, only: fsym_overlap
    use fsym_status, only: FSYM_ERR_BAD_REQUEST, FSYM_ERR_BAD_ARGUMENT, FSYM_ERR_NO_GRADIENT
    use fsym_scheme, only: OP_GRAD_KICK
    use fsym_oscillator, only: fsym_stability_interval
    use fsym_checkpoint, only: fsym_crc32_table, fsym_crc32_feed, CRC_ONES
    implicit none
    private

    integer, parameter, public :: LEGACY_MAGIC = 20260  !! IW(1) of a set-up work array
    integer, parameter, public :: LEGACY_KO = 8         !! IW index of the op codes
    integer, parameter, public :: LEGACY_KC = KERNEL_NPACK + 1  !! RW index of the coefficients
    integer, parameter, public :: LEGACY_TAIL = 5       !! IW words after the op codes
    integer, parameter, public :: LEGACY_GUARD = 1718840135  !! last word of a set-up IW

    !> The caller's EXTERNAL acceleration (and gradient) routines as a force model.
    type, extends(force_model_t), public :: legacy_model_t
        procedure(fsym_legacy_accel), pointer, nopass :: accel => null()  !! ACCEL
        procedure(fsym_legacy_grad), pointer, nopass :: grad => null()    !! GRAD
        procedure(fsym_legacy_freq), pointer, nopass :: freq => null()    !! FREQ (FSYMGD)
    contains
        procedure :: local_frequency => legacy_frequency  !! calls FREQ
        procedure :: has_frequency => legacy_has_frequency  !! FREQ given
        procedure :: acceleration => legacy_acceleration  !! calls ACCEL
        procedure :: gradient => legacy_gradient          !! calls GRAD
        procedure :: has_gradient => legacy_has_gradient  !! GRAD given
    end type legacy_model_t

    public :: legacy_sizes, legacy_scheme_sizes, legacy_setup, legacy_ok, legacy_check
    public :: legacy_load, legacy_store, legacy_steps, legacy_busy, legacy_seal, legacy_xstar

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
        allocate (cat, source=fsym_catalogue())
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
        liw = LEGACY_KO - 1 + s%nop + LEGACY_TAIL
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
        integer :: need_r, need_i, k
        real(wp) :: xstar
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
        call fsym_stability_interval(s, xstar)
        k = LEGACY_KO + s%nop
        iw(k + 1:k + 2) = transfer(xstar, iw(1:2))
        iw(k + 4) = LEGACY_GUARD
        call legacy_seal(liw, iw, lrw, rw)
        info = FSYM_SUCCESS
    end subroutine legacy_setup

    !> Store the checksum of IW (and of the coefficients in RW) after a change of IW.
    pure subroutine legacy_seal(liw, iw, lrw, rw)
        integer, intent(in) :: liw, lrw          !! lengths (checked by legacy_check)
        integer, intent(inout) :: iw(liw)        !! integer work array
        real(wp), intent(in) :: rw(lrw)          !! real work array
        iw(LEGACY_KO + iw(4) + 3) = work_crc(liw, iw, lrw, rw)
    end subroutine legacy_seal

    !> Set (`on`) or clear the busy flag of IW and seal it again.
    pure subroutine legacy_busy(liw, iw, lrw, rw, on)
        integer, intent(in) :: liw, lrw          !! lengths (checked by legacy_check)
        integer, intent(inout) :: iw(liw)        !! integer work array
        real(wp), intent(in) :: rw(lrw)          !! real work array
        logical, intent(in) :: on                !! busy or not
        iw(LEGACY_KO + iw(4)) = merge(1, 0, on)
        call legacy_seal(liw, iw, lrw, rw)
    end subroutine legacy_busy

    !> The method's stability limit x* kept in IW (for the guard of FSYMGD).
    pure real(wp) function legacy_xstar(liw, iw) result(xstar)
        integer, intent(in) :: liw               !! length (checked by legacy_check)
        integer, intent(in) :: iw(liw)           !! integer work array
        integer :: k
        k = LEGACY_KO + iw(4)
        xstar = transfer(iw(k + 1:k + 2), xstar)
    end function legacy_xstar

    !> CRC-32 (IEEE 802.3, as `fsym_crc32`) of IW(1:K+2), IW(K+4) (K = 8 + NOP) and the bits
    !> of C and U in RW, as a default integer.
    pure integer function work_crc(liw, iw, lrw, rw) result(c)
        integer, intent(in) :: liw, lrw
        integer, intent(in) :: iw(liw)
        real(wp), intent(in) :: rw(lrw)
        integer(int64) :: table(0:255), crc, t
        integer :: j, k, nop
        table = fsym_crc32_table()
        nop = iw(4); k = LEGACY_KO + nop
        crc = CRC_ONES
        do j = 1, k + 4
            if (j == k + 3) cycle
            crc = fsym_crc32_feed(crc, int(iw(j), int64), 4, table)
        end do
        do j = LEGACY_KC, LEGACY_KC + 2 * nop - 1
            crc = fsym_crc32_feed(crc, transfer(rw(j), t), 8, table)
        end do
        crc = ieor(crc, CRC_ONES)
        if (crc > huge(c)) crc = crc - 4294967296_int64     ! as a signed 32-bit word
        c = int(crc)
    end function work_crc

    !> True when `iw` was set up by FSYMIN for (nd, n) and the lengths suffice.
    pure logical function legacy_ok(nd, n, lrw, liw, iw, rw)
        integer, intent(in) :: nd, n, lrw, liw   !! dimensions and lengths given by the caller
        integer, intent(in) :: iw(liw)           !! integer work array
        real(wp), intent(in) :: rw(lrw)          !! real work array
        legacy_ok = legacy_check(nd, n, lrw, liw, iw, rw) == FSYM_SUCCESS
    end function legacy_ok

    !> Why the work arrays cannot be used for (nd, n): FSYM_ERR_NOT_INITIALIZED when `iw`
    !> was not set up by FSYMIN (or is too short to tell), FSYM_ERR_SHAPE when it was set up
    !> for other dimensions, FSYM_ERR_WORK_SIZE when LRW or LIW is shorter than it needs,
    !> FSYM_ERR_BUSY when a call on them is in progress (the caller's ACCEL called in again);
    !> FSYM_SUCCESS when they are fine. Any word of IW changed since the library wrote it (or
    !> a coefficient of RW) fails the checksum or the guard word: FSYM_ERR_NOT_INITIALIZED.
    !> Lengths are compared in 64-bit arithmetic; no index outside IW or RW is read.
    pure integer function legacy_check(nd, n, lrw, liw, iw, rw) result(info)
        integer, intent(in) :: nd, n, lrw, liw   !! dimensions and lengths given by the caller
        integer, intent(in) :: iw(liw)           !! integer work array
        real(wp), intent(in) :: rw(lrw)          !! real work array
        integer :: k
        info = FSYM_ERR_NOT_INITIALIZED
        if (liw < 7) return
        if (iw(1) /= LEGACY_MAGIC .or. iw(4) < 1 .or. iw(5) < 1) return
        info = FSYM_ERR_WORK_SIZE
        if (int(liw, ik) < LEGACY_KO - 1 + int(iw(4), ik) + LEGACY_TAIL) return
        if (int(lrw, ik) < LEGACY_KC - 1 + 2 * int(iw(4), ik)) return
        k = LEGACY_KO + iw(4)
        info = FSYM_ERR_NOT_INITIALIZED
        if (iw(k + 4) /= LEGACY_GUARD) return
        if (iw(k + 3) /= work_crc(liw, iw, lrw, rw)) return
        info = FSYM_ERR_BUSY
        if (iw(k) /= 0) return
        info = FSYM_ERR_SHAPE
        if (iw(2) /= nd .or. iw(3) /= n) return
        info = FSYM_ERR_WORK_SIZE
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
        associate (unused => stat); end associate   ! the EXTERNAL has no status
        call self%accel(size(q, 1), size(q, 2), q, a)
    end subroutine legacy_acceleration

    subroutine legacy_gradient(self, q, a, g, stat)
        class(legacy_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)   !! positions (d, n)
        real(wp), intent(in), contiguous :: a(:, :)   !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)  !! gradient term (d, n)
        integer, intent(inout) :: stat                !! unchanged (GRAD has no status)
        associate (unused => stat); end associate   ! the EXTERNAL has no status
        call self%grad(size(q, 1), size(q, 2), q, a, g)
    end subroutine legacy_gradient

    subroutine legacy_frequency(self, q, omega2, r, stat)
        class(legacy_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)   !! positions (d, n)
        real(wp), intent(out) :: omega2               !! largest omega^2
        real(wp), intent(out) :: r                    !! distance where it occurs
        integer, intent(inout) :: stat                !! unchanged (FREQ has no status)
        associate (unused => stat); end associate   ! the EXTERNAL has no status
        call self%freq(size(q, 1), size(q, 2), q, omega2, r)
    end subroutine legacy_frequency

    logical function legacy_has_frequency(self)
        class(legacy_model_t), intent(in) :: self  !! the model
        legacy_has_frequency = associated(self%freq)
    end function legacy_has_frequency

    !> The body of FSYMST and FSYMGD: NSTEP steps with the caller's routines in `model`
    !> (`model%grad` null: no gradient term), guarded with limit `frac` x* when `frac` is
    !> given. Checks the work arrays (checksum, busy flag), refuses X and V sharing memory,
    !> marks IW busy while the caller's routines run, stores the steps done in IW(7).
    subroutine legacy_steps(nd, n, x, v, h, nstep, model, rw, lrw, iw, liw, info, frac)
        integer, intent(in) :: nd, n                !! dimensions, bodies
        real(wp), intent(inout) :: x(nd, n)         !! positions
        real(wp), intent(inout) :: v(nd, n)         !! velocities
        real(wp), intent(in) :: h                   !! step
        integer, intent(in) :: nstep                !! number of steps
        type(legacy_model_t), intent(inout) :: model  !! the caller's routines
        integer, intent(in) :: lrw, liw             !! lengths of RW and IW
        real(wp), intent(inout) :: rw(lrw)          !! work array set up by FSYMIN
        integer, intent(inout) :: iw(liw)           !! work array set up by FSYMIN
        integer, intent(out) :: info                !! status
        real(wp), intent(in), optional :: frac      !! guard: fraction of x*
        type(kernel_state_t) :: ks
        type(guard_t) :: g
        integer :: nop, kw, req, at, into, given
        integer(ik) :: ndone
        info = legacy_check(nd, n, lrw, liw, iw, rw)
        if (info /= FSYM_SUCCESS) return        ! IW may be short or foreign: write nothing
        nop = iw(4)
        if (nstep < 1) then
            info = FSYM_ERR_BAD_ARGUMENT; return
        end if
        if (fsym_overlap(x, v)) then
            info = FSYM_ERR_BAD_ARGUMENT; return
        end if
        call legacy_load(liw, iw, rw(1:KERNEL_NPACK), ks, info)
        if (info /= FSYM_SUCCESS) return
        call fsym_kernel_request(ks, req, at, into, given)
        if (req /= REQ_NONE) then
            info = FSYM_ERR_BAD_REQUEST; return     ! a reverse-communication step is open
        end if
        if (.not. associated(model%grad)) then
            if (any(iw(LEGACY_KO:LEGACY_KO + nop - 1) == OP_GRAD_KICK)) then
                info = FSYM_ERR_NO_GRADIENT; return
            end if
        end if
        kw = LEGACY_KC + 2 * nop
        call legacy_busy(liw, iw, lrw, rw, .true.)
        if (present(frac)) then
            g%on = .true.
            g%xstar = legacy_xstar(liw, iw)
            g%limit = g%xstar
            if (frac > 0.0_wp) g%limit = min(frac, 1.0e6_wp) * g%xstar
            call fsym_guard_run(g, nop, iw(LEGACY_KO:LEGACY_KO + nop - 1), &
                                rw(LEGACY_KC:LEGACY_KC + nop - 1), rw(LEGACY_KC + nop:kw - 1), &
                                model, ks, x, v, rw(kw:), h, int(nstep, ik), ndone, info, &
                                .false.)
        else
            call fsym_kernel_run(nop, iw(LEGACY_KO:LEGACY_KO + nop - 1), &
                                 rw(LEGACY_KC:LEGACY_KC + nop - 1), rw(LEGACY_KC + nop:kw - 1), &
                                 model, ks, x, v, rw(kw), h, int(nstep, ik), ndone, info)
        end if
        iw(7) = int(ndone)
        call legacy_store(ks, rw(1:KERNEL_NPACK))
        call legacy_busy(liw, iw, lrw, rw, .false.)
    end subroutine legacy_steps

    logical function legacy_has_gradient(self)
        class(legacy_model_t), intent(in) :: self  !! the model
        legacy_has_gradient = associated(self%grad)
    end function legacy_has_gradient

end module fsym_legacy_work
