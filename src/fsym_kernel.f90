!> The one splitting kernel. It runs the stages of any scheme on explicit arrays `q(d,n)`,
!> `v(d,n)` and a caller-owned work array, and asks for forces by reverse communication: it
!> returns a request (force at the state, gradient term at the state, force at the
!> extrapolated point), the caller fills the slot named by the request and resumes it, until
!> the step is done. The modern integrator, the F77 layer and the C API all drive this one
!> kernel, so they share its arithmetic bit for bit.
!>
!> It never allocates and does no I/O. A step either completes or leaves `q`, `v` (and the
!> compensation terms) exactly as they were on entry: every supplied force and the final
!> state are checked for NaN/Inf.
!>
!> Work layout: `w(d, n, nslot)` holds named slots (`SLOT_*`); `fsym_kernel_layout` tells
!> which slots a scheme needs and writes their positions into the integer state `iw`, so
!> methods without gradient or extrapolation, and runs without compensation, pay no memory
!> for them. First-same-as-last: the force at the end of a step stays valid in `SLOT_A` and
!> is reused by the next step when the caller has not moved `q` in between (checked bitwise
!> against `SLOT_QLAST`).
module fsym_kernel
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fsym_kinds, only: wp, ik
    use fsym_status
    use fsym_scheme, only: OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK
    implicit none
    private

    ! requests returned by fsym_kernel_resume
    integer, parameter, public :: REQ_DONE = 0           !! the step is complete
    integer, parameter, public :: REQ_FORCE = 1          !! fill SLOT_A with a(q) at the state q
    integer, parameter, public :: REQ_GRADIENT = 2       !! fill SLOT_G with g(q); a(q) is in SLOT_A
    integer, parameter, public :: REQ_FORCE_SHIFTED = 3  !! fill SLOT_AE with a(x), x in SLOT_QE
    integer, parameter, public :: REQ_ERROR = -1         !! failed; state restored, see stat

    ! kinds of work slot
    integer, parameter, public :: SLOT_A = 1      !! acceleration at the state
    integer, parameter, public :: SLOT_G = 2      !! gradient term at the state
    integer, parameter, public :: SLOT_QE = 3     !! extrapolated position
    integer, parameter, public :: SLOT_AE = 4     !! acceleration at the extrapolated position
    integer, parameter, public :: SLOT_Q0 = 5     !! q on entry (restored on failure)
    integer, parameter, public :: SLOT_V0 = 6     !! v on entry
    integer, parameter, public :: SLOT_QLAST = 7  !! q at the end of the last step (FSAL check)
    integer, parameter, public :: SLOT_QC = 8     !! compensation term of q (Kahan)
    integer, parameter, public :: SLOT_VC = 9     !! compensation term of v
    integer, parameter, public :: SLOT_QC0 = 10   !! compensation of q on entry
    integer, parameter, public :: SLOT_VC0 = 11   !! compensation of v on entry
    integer, parameter, public :: NSLOT_KINDS = 11  !! number of slot kinds

    ! integer state
    integer, parameter, public :: KW_PC = 1          !! next stage to run
    integer, parameter, public :: KW_REQ = 2         !! outstanding request
    integer, parameter, public :: KW_HAVE_A = 3      !! SLOT_A holds a(q)
    integer, parameter, public :: KW_HAVE_G = 4      !! SLOT_G holds g(q)
    integer, parameter, public :: KW_HAVE_X = 5      !! SLOT_AE holds a at the shifted point
    integer, parameter, public :: KW_ACTIVE = 6      !! a step is in progress
    integer, parameter, public :: KW_COMP = 7        !! compensated summation on
    integer, parameter, public :: KW_NSLOT = 8       !! number of slots in use
    integer, parameter, public :: KW_MAP = 9         !! KW_MAP-1+k: slot index of kind k
    integer, parameter, public :: KERNEL_NIW = KW_MAP + NSLOT_KINDS - 1  !! length of `iw`

    ! real state
    integer, parameter, public :: KR_H = 1        !! step of the step in progress
    integer, parameter, public :: KR_XSHIFT = 2   !! u h^2 of the cached extrapolated force
    integer, parameter, public :: KERNEL_NRW = 2  !! length of `rw`

    public :: fsym_kernel_layout, fsym_kernel_slot, fsym_kernel_begin, fsym_kernel_resume
    public :: fsym_kernel_abort, fsym_kernel_invalidate, fsym_all_finite

contains

    !> Choose the work slots a scheme needs and reset the kernel state. `nslot` slots of
    !> d*n reals each make the work array.
    pure subroutine fsym_kernel_layout(op, compensated, iw, rw, nslot)
        integer, intent(in) :: op(:)                 !! the scheme's op codes
        logical, intent(in) :: compensated           !! Kahan-compensated updates
        integer, intent(out) :: iw(KERNEL_NIW)       !! kernel integer state
        real(wp), intent(out) :: rw(KERNEL_NRW)      !! kernel real state
        integer, intent(out) :: nslot                !! slots needed
        logical :: need(NSLOT_KINDS)
        integer :: k
        need = .false.
        need([SLOT_A, SLOT_Q0, SLOT_V0, SLOT_QLAST]) = .true.
        need(SLOT_G) = any(op == OP_GRAD_KICK)
        need(SLOT_QE) = any(op == OP_EXTRAP_KICK)
        need(SLOT_AE) = need(SLOT_QE)
        need([SLOT_QC, SLOT_VC, SLOT_QC0, SLOT_VC0]) = compensated
        iw = 0
        rw = 0.0_wp
        nslot = 0
        do k = 1, NSLOT_KINDS
            if (need(k)) then
                nslot = nslot + 1
                iw(KW_MAP - 1 + k) = nslot
            else
                iw(KW_MAP - 1 + k) = 1      ! never touched
            end if
        end do
        iw(KW_NSLOT) = nslot
        iw(KW_COMP) = merge(1, 0, compensated)
    end subroutine fsym_kernel_layout

    !> Index in the work array of a slot kind.
    pure integer function fsym_kernel_slot(iw, kind)
        integer, intent(in) :: iw(KERNEL_NIW)  !! kernel integer state
        integer, intent(in) :: kind            !! a `SLOT_*` kind
        fsym_kernel_slot = iw(KW_MAP - 1 + kind)
    end function fsym_kernel_slot

    !> True when every element is finite (one summation; an element-wise look only when the
    !> sum is not finite).
    pure logical function fsym_all_finite(m, x)
        integer, intent(in) :: m         !! number of elements
        real(wp), intent(in) :: x(m)     !! values
        real(wp) :: s
        s = sum(x)
        if (abs(s) <= huge(s)) then
            fsym_all_finite = .true.
        else
            fsym_all_finite = all(ieee_is_finite(x))
        end if
    end function fsym_all_finite

    !> Forget every cached force (call after changing q behind the kernel's back).
    pure subroutine fsym_kernel_invalidate(iw)
        integer, intent(inout) :: iw(KERNEL_NIW)  !! kernel integer state
        iw(KW_HAVE_A) = 0; iw(KW_HAVE_G) = 0; iw(KW_HAVE_X) = 0
    end subroutine fsym_kernel_invalidate

    !> Start a step of size h: check h and the state, save the state for restoring, and keep
    !> the cached end-of-step force only if q is bitwise the q it was computed at.
    subroutine fsym_kernel_begin(d, n, q, v, h, w, nslot, iw, rw, stat)
        integer, intent(in) :: d, n, nslot            !! dimensions, particles, slots
        real(wp), intent(in) :: q(d, n), v(d, n)      !! state
        real(wp), intent(in) :: h                     !! step
        real(wp), intent(inout) :: w(d, n, nslot)     !! work slots
        integer, intent(inout) :: iw(KERNEL_NIW)      !! kernel integer state
        real(wp), intent(inout) :: rw(KERNEL_NRW)     !! kernel real state
        integer, intent(out) :: stat                  !! FSYM_SUCCESS or an error code
        integer :: sl
        if (.not. (h /= 0.0_wp .and. abs(h) <= huge(h))) then
            stat = FSYM_ERR_BAD_STEP; return
        end if
        if (.not. (fsym_all_finite(d * n, q) .and. fsym_all_finite(d * n, v))) then
            stat = FSYM_ERR_NONFINITE_STATE; return
        end if
        if (iw(KW_HAVE_A) /= 0) then
            sl = iw(KW_MAP - 1 + SLOT_QLAST)
            if (any(q /= w(:, :, sl))) call fsym_kernel_invalidate(iw)
        end if
        w(:, :, iw(KW_MAP - 1 + SLOT_Q0)) = q
        w(:, :, iw(KW_MAP - 1 + SLOT_V0)) = v
        if (iw(KW_COMP) /= 0) then
            w(:, :, iw(KW_MAP - 1 + SLOT_QC0)) = w(:, :, iw(KW_MAP - 1 + SLOT_QC))
            w(:, :, iw(KW_MAP - 1 + SLOT_VC0)) = w(:, :, iw(KW_MAP - 1 + SLOT_VC))
        end if
        rw(KR_H) = h
        iw(KW_PC) = 1
        iw(KW_REQ) = REQ_DONE
        iw(KW_ACTIVE) = 1
        stat = FSYM_SUCCESS
    end subroutine fsym_kernel_begin

    !> Undo the step in progress: restore q, v and the compensation terms saved by
    !> `fsym_kernel_begin`, and forget every cached force.
    subroutine fsym_kernel_abort(d, n, q, v, w, nslot, iw)
        integer, intent(in) :: d, n, nslot            !! dimensions, particles, slots
        real(wp), intent(inout) :: q(d, n), v(d, n)   !! state, restored
        real(wp), intent(inout) :: w(d, n, nslot)     !! work slots
        integer, intent(inout) :: iw(KERNEL_NIW)      !! kernel integer state
        if (iw(KW_ACTIVE) /= 0) then
            q = w(:, :, iw(KW_MAP - 1 + SLOT_Q0))
            v = w(:, :, iw(KW_MAP - 1 + SLOT_V0))
            if (iw(KW_COMP) /= 0) then
                w(:, :, iw(KW_MAP - 1 + SLOT_QC)) = w(:, :, iw(KW_MAP - 1 + SLOT_QC0))
                w(:, :, iw(KW_MAP - 1 + SLOT_VC)) = w(:, :, iw(KW_MAP - 1 + SLOT_VC0))
            end if
        end if
        call fsym_kernel_invalidate(iw)
        iw(KW_ACTIVE) = 0
        iw(KW_REQ) = REQ_DONE
    end subroutine fsym_kernel_abort

    !> Run stages until a force is needed or the step is complete. On entry with a request
    !> outstanding, the caller has filled the requested slot; it is checked and used.
    !> `req` tells what to do next (`REQ_*`); on `REQ_ERROR` the state is restored and
    !> `stat` says why. `nf`/`ng` count the force and gradient evaluations supplied.
    subroutine fsym_kernel_resume(nop, op, c, u, d, n, q, v, w, nslot, iw, rw, nf, ng, req, stat)
        integer, intent(in) :: nop                    !! number of stages
        integer, intent(in) :: op(nop)                !! op codes
        real(wp), intent(in) :: c(nop), u(nop)        !! stage coefficients
        integer, intent(in) :: d, n, nslot            !! dimensions, particles, slots
        real(wp), intent(inout) :: q(d, n), v(d, n)   !! state
        real(wp), intent(inout) :: w(d, n, nslot)     !! work slots
        integer, intent(inout) :: iw(KERNEL_NIW)      !! kernel integer state
        real(wp), intent(inout) :: rw(KERNEL_NRW)     !! kernel real state
        integer(ik), intent(inout) :: nf, ng          !! evaluation counters
        integer, intent(out) :: req                   !! next request
        integer, intent(out) :: stat                  !! FSYM_SUCCESS or an error code
        integer :: k, ia, ig, iqe, iae, iqc, ivc
        real(wp) :: h, shift
        logical :: comp

        stat = FSYM_SUCCESS
        if (iw(KW_ACTIVE) == 0) then
            req = REQ_ERROR; stat = FSYM_ERR_BAD_REQUEST; return
        end if
        ia = iw(KW_MAP - 1 + SLOT_A); ig = iw(KW_MAP - 1 + SLOT_G)
        iqe = iw(KW_MAP - 1 + SLOT_QE); iae = iw(KW_MAP - 1 + SLOT_AE)
        iqc = iw(KW_MAP - 1 + SLOT_QC); ivc = iw(KW_MAP - 1 + SLOT_VC)
        comp = iw(KW_COMP) /= 0
        h = rw(KR_H)

        ! accept what the caller supplied
        select case (iw(KW_REQ))
        case (REQ_FORCE)
            if (.not. fsym_all_finite(d * n, w(:, :, ia))) then
                call fail(FSYM_ERR_NONFINITE_FORCE); return
            end if
            iw(KW_HAVE_A) = 1; nf = nf + 1
        case (REQ_GRADIENT)
            if (.not. fsym_all_finite(d * n, w(:, :, ig))) then
                call fail(FSYM_ERR_NONFINITE_FORCE); return
            end if
            iw(KW_HAVE_G) = 1; ng = ng + 1
        case (REQ_FORCE_SHIFTED)
            if (.not. fsym_all_finite(d * n, w(:, :, iae))) then
                call fail(FSYM_ERR_NONFINITE_FORCE); return
            end if
            iw(KW_HAVE_X) = 1; nf = nf + 1
        end select
        iw(KW_REQ) = REQ_DONE

        do while (iw(KW_PC) <= nop)
            k = iw(KW_PC)
            select case (op(k))
            case (OP_DRIFT)
                if (comp) then
                    call add_compensated(d * n, q, w(:, :, iqc), c(k) * h, v)
                else
                    q = q + (c(k) * h) * v
                end if
                call fsym_kernel_invalidate(iw)
            case (OP_KICK)
                if (iw(KW_HAVE_A) == 0) then
                    call ask(REQ_FORCE); return
                end if
                if (comp) then
                    call add_compensated(d * n, v, w(:, :, ivc), c(k) * h, w(:, :, ia))
                else
                    v = v + (c(k) * h) * w(:, :, ia)
                end if
            case (OP_GRAD_KICK)
                if (iw(KW_HAVE_A) == 0) then
                    call ask(REQ_FORCE); return
                end if
                if (iw(KW_HAVE_G) == 0) then
                    call ask(REQ_GRADIENT); return
                end if
                if (comp) then
                    call add_compensated2(d * n, v, w(:, :, ivc), c(k) * h, w(:, :, ia), &
                                          u(k) * h**3, w(:, :, ig))
                else
                    v = v + ((c(k) * h) * w(:, :, ia) + (u(k) * h**3) * w(:, :, ig))
                end if
            case (OP_EXTRAP_KICK)
                if (iw(KW_HAVE_A) == 0) then
                    call ask(REQ_FORCE); return
                end if
                shift = u(k) * h * h
                if (iw(KW_HAVE_X) == 0 .or. rw(KR_XSHIFT) /= shift) then
                    w(:, :, iqe) = q + shift * w(:, :, ia)
                    rw(KR_XSHIFT) = shift
                    iw(KW_HAVE_X) = 0
                    call ask(REQ_FORCE_SHIFTED); return
                end if
                if (comp) then
                    call add_compensated(d * n, v, w(:, :, ivc), c(k) * h, w(:, :, iae))
                else
                    v = v + (c(k) * h) * w(:, :, iae)
                end if
            end select
            iw(KW_PC) = k + 1
        end do

        if (.not. (fsym_all_finite(d * n, q) .and. fsym_all_finite(d * n, v))) then
            call fail(FSYM_ERR_NONFINITE_STATE); return
        end if
        if (iw(KW_HAVE_A) /= 0) w(:, :, iw(KW_MAP - 1 + SLOT_QLAST)) = q
        iw(KW_ACTIVE) = 0
        req = REQ_DONE

    contains

        subroutine ask(what)
            integer, intent(in) :: what
            iw(KW_REQ) = what
            req = what
        end subroutine ask

        subroutine fail(code)
            integer, intent(in) :: code
            call fsym_kernel_abort(d, n, q, v, w, nslot, iw)
            req = REQ_ERROR
            stat = code
        end subroutine fail

    end subroutine fsym_kernel_resume

    !> x <- x + s*y with Kahan compensation carried in e.
    pure subroutine add_compensated(m, x, e, s, y)
        integer, intent(in) :: m
        real(wp), intent(inout) :: x(m), e(m)
        real(wp), intent(in) :: s, y(m)
        real(wp) :: inc, t
        integer :: i
        do i = 1, m
            inc = s * y(i) - e(i)
            t = x(i) + inc
            e(i) = (t - x(i)) - inc
            x(i) = t
        end do
    end subroutine add_compensated

    !> x <- x + s*y + r*z with Kahan compensation carried in e.
    pure subroutine add_compensated2(m, x, e, s, y, r, z)
        integer, intent(in) :: m
        real(wp), intent(inout) :: x(m), e(m)
        real(wp), intent(in) :: s, y(m), r, z(m)
        real(wp) :: inc, t
        integer :: i
        do i = 1, m
            inc = (s * y(i) + r * z(i)) - e(i)
            t = x(i) + inc
            e(i) = (t - x(i)) - inc
            x(i) = t
        end do
    end subroutine add_compensated2

end module fsym_kernel
