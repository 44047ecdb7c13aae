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
    use fsym_kepler, only: kepler_field, kepler_field_gradient
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

    ! Kepler path: bodies per block of the block path, and up to how many planar bodies run
    ! one after the other on scalars (the least overhead per step)
    integer, parameter :: KEPLER_BLOCK = 64
    integer, parameter :: KEPLER_SCALAR_MAX = 4

    public :: fsym_kernel_layout, fsym_kernel_slot, fsym_kernel_begin, fsym_kernel_resume
    public :: fsym_kernel_abort, fsym_kernel_invalidate, fsym_all_finite
    public :: fsym_kernel_run_kepler

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
    !> sum is not finite). The sum runs in 16 interleaved partial sums so that it vectorises
    !> (a single running sum is a chain of dependent additions: 4 cycles per element).
    pure logical function fsym_all_finite(m, x)
        integer, intent(in) :: m         !! number of elements
        real(wp), intent(in) :: x(m)     !! values
        integer, parameter :: nacc = 16
        real(wp) :: s, acc(nacc)
        integer :: i, mb
        if (m < nacc) then
            s = sum(x)
        else
            mb = m - mod(m, nacc)
            acc = x(1:nacc)
            do i = nacc + 1, mb, nacc
                acc = acc + x(i:i + nacc - 1)
            end do
            s = sum(acc) + sum(x(mb + 1:m))
        end if
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
        case default
            ! nothing else can occur here
        end select
        iw(KW_REQ) = REQ_DONE

        do while (iw(KW_PC) <= nop)
            k = iw(KW_PC)
            select case (op(k))
            case (OP_DRIFT)
                if (comp) then
                    call add_compensated(d * n, q, w(:, :, iqc), c(k) * h, v)
                else
                    call stage_add(d * n, q, v, c(k) * h)
                end if
                call fsym_kernel_invalidate(iw)
            case (OP_KICK)
                if (iw(KW_HAVE_A) == 0) then
                    call ask(REQ_FORCE); return
                end if
                if (comp) then
                    call add_compensated(d * n, v, w(:, :, ivc), c(k) * h, w(:, :, ia))
                else
                    call stage_add(d * n, v, w(:, :, ia), c(k) * h)
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
                    call stage_grad_kick(d * n, v, w(:, :, ia), w(:, :, ig), c(k) * h, &
                                         u(k) * h**3)
                end if
            case (OP_EXTRAP_KICK)
                if (iw(KW_HAVE_A) == 0) then
                    call ask(REQ_FORCE); return
                end if
                shift = u(k) * h * h
                if (iw(KW_HAVE_X) == 0 .or. rw(KR_XSHIFT) /= shift) then
                    call stage_shift(d * n, w(:, :, iqe), q, w(:, :, ia), shift)
                    rw(KR_XSHIFT) = shift
                    iw(KW_HAVE_X) = 0
                    call ask(REQ_FORCE_SHIFTED); return
                end if
                if (comp) then
                    call add_compensated(d * n, v, w(:, :, ivc), c(k) * h, w(:, :, iae))
                else
                    call stage_add(d * n, v, w(:, :, iae), c(k) * h)
                end if
            case default
                ! nothing else can occur here
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

    !> `nsteps` steps for the Kepler force of the library (`kepler_field`: n bodies about a
    !> fixed centre of parameter mu) without reverse communication and without a return to
    !> the caller between steps. Each step has the stages, the stage arithmetic (`axpy`,
    !> `axpy2`, the operations `fsym_kernel_resume` applies), the force-reuse rules, checks
    !> and counters of `fsym_kernel_begin` + `fsym_kernel_resume` driven with that force, so
    !> the state after k steps is bitwise the state after k such steps. Up to
    !> `KEPLER_SCALAR_MAX` planar bodies run one after the other, each on scalars for all
    !> its steps (`kepler_run_2d`); more bodies run stage by stage on blocks of
    !> `KEPLER_BLOCK` (the loops vectorise and a block stays in cache).
    !>
    !> On return `ndone` steps are complete. On failure (`stat` /= 0) q and v are the state
    !> after `ndone` steps (the failing step is undone), the cache is forgotten and
    !> iw(KW_PC) names the stage that failed (0: rejected on entry; with several failing
    !> bodies in the block path it may be a later stage than the general path names). Not
    !> for compensated runs (stat = FSYM_ERR_BAD_REQUEST: use the general path).
    subroutine fsym_kernel_run_kepler(nop, op, c, u, d, n, q, v, h, mu, nsteps, w, nslot, &
                                      iw, rw, nf, ng, ndone, stat)
        integer, intent(in) :: nop                    !! number of stages
        integer, intent(in) :: op(nop)                !! op codes
        real(wp), intent(in) :: c(nop), u(nop)        !! stage coefficients
        integer, intent(in) :: d, n, nslot            !! dimensions, bodies, slots
        real(wp), intent(inout) :: q(d, n), v(d, n)   !! state
        real(wp), intent(in) :: h                     !! step
        real(wp), intent(in) :: mu                    !! G M of the centre
        integer(ik), intent(in) :: nsteps             !! steps to take (none if < 1)
        real(wp), intent(inout) :: w(d, n, nslot)     !! work slots
        integer, intent(inout) :: iw(KERNEL_NIW)      !! kernel integer state
        real(wp), intent(inout) :: rw(KERNEL_NRW)     !! kernel real state
        integer(ik), intent(inout) :: nf, ng          !! evaluation counters
        integer(ik), intent(out) :: ndone             !! steps completed
        integer, intent(out) :: stat                  !! FSYM_SUCCESS or an error code

        ndone = 0
        stat = FSYM_SUCCESS
        if (nsteps < 1) return
        if (iw(KW_COMP) /= 0) then
            stat = FSYM_ERR_BAD_REQUEST; return
        end if
        if (d == 2) then
            call begin_2d(n, q, v, h, w, nslot, iw, rw, stat)
        else
            call fsym_kernel_begin(d, n, q, v, h, w, nslot, iw, rw, stat)
        end if
        if (stat /= FSYM_SUCCESS) then
            iw(KW_PC) = 0; return      ! rejected before the first stage
        end if
        if (d == 2 .and. n <= KEPLER_SCALAR_MAX) then
            call kepler_run_2d(nop, op, c, u, n, q, v, h, mu, nsteps, w, nslot, iw, rw, nf, ng, &
                               ndone, stat)
        else
            call kepler_run_blocks(nop, op, c, u, d, n, q, v, h, mu, nsteps, w, nslot, iw, rw, &
                                   nf, ng, ndone, stat)
        end if
    end subroutine fsym_kernel_run_kepler

    !> The block path of `fsym_kernel_run_kepler` (entered after `fsym_kernel_begin`, which
    !> saved the entry state in SLOT_Q0/SLOT_V0): every step runs all stages on one block of
    !> bodies after the other, and checks the block's new state. Steps save nothing: when step kf
    !> fails, the state of its start is made again by running kf - 1 steps from the saved
    !> entry state (bitwise the same steps).
    subroutine kepler_run_blocks(nop, op, c, u, d, n, q, v, h, mu, nsteps, w, nslot, iw, rw, &
                                 nf, ng, ndone, stat)
        integer, intent(in) :: nop, op(nop), d, n, nslot
        real(wp), intent(in) :: c(nop), u(nop), h, mu
        integer(ik), intent(in) :: nsteps
        real(wp), intent(inout) :: q(d, n), v(d, n), w(d, n, nslot)
        integer, intent(inout) :: iw(KERNEL_NIW)
        real(wp), intent(inout) :: rw(KERNEL_NRW)
        integer(ik), intent(inout) :: nf, ng
        integer(ik), intent(out) :: ndone
        integer, intent(out) :: stat
        integer :: ia, ig, iqe, iae, entry_have(3), fstage
        integer :: j0, j1, mb, code      ! block in work, and the error found (in `advance`)
        integer(ik) :: kf, nf_entry, ng_entry, pf, pg, pf0, pg0
        real(wp) :: entry_xshift

        ia = iw(KW_MAP - 1 + SLOT_A); ig = iw(KW_MAP - 1 + SLOT_G)
        iqe = iw(KW_MAP - 1 + SLOT_QE); iae = iw(KW_MAP - 1 + SLOT_AE)
        entry_have = iw(KW_HAVE_A:KW_HAVE_X); entry_xshift = rw(KR_XSHIFT)
        nf_entry = nf; ng_entry = ng
        call advance(nsteps, kf, fstage, pf, pg)
        stat = code
        if (stat == FSYM_SUCCESS) then
            ndone = nsteps
            if (iw(KW_HAVE_A) /= 0) w(:, :, iw(KW_MAP - 1 + SLOT_QLAST)) = q
        else
            q = w(:, :, iw(KW_MAP - 1 + SLOT_Q0))
            v = w(:, :, iw(KW_MAP - 1 + SLOT_V0))
            iw(KW_HAVE_A:KW_HAVE_X) = entry_have; rw(KR_XSHIFT) = entry_xshift
            nf = nf_entry; ng = ng_entry
            call advance(kf - 1, kf, fstage, pf0, pg0)   ! cannot fail
            nf = nf + pf; ng = ng + pg
            call fsym_kernel_invalidate(iw)
            iw(KW_PC) = fstage
            ndone = kf - 1
        end if
        iw(KW_ACTIVE) = 0
        iw(KW_REQ) = REQ_DONE

    contains

        !> Up to `nst` steps from the current state and cache. On failure at step `kfail`
        !> (stage `stage`, error in `code`), it stops there and returns in `dnf`, `dng` the
        !> evaluations that step had made; the state is then not restored.
        subroutine advance(nst, kfail, stage, dnf, dng)
            integer(ik), intent(in) :: nst
            integer(ik), intent(inout) :: kfail
            integer, intent(inout) :: stage
            integer(ik), intent(out) :: dnf, dng
            integer :: k, have0(3)
            integer(ik) :: istep, nf0, ng0
            real(wp) :: shift, xshift0
            code = FSYM_SUCCESS
            do istep = 1, nst
                ! every block starts from the same cache state and counts from the same
                ! counters
                have0 = iw(KW_HAVE_A:KW_HAVE_X); xshift0 = rw(KR_XSHIFT)
                nf0 = nf; ng0 = ng
                do j0 = 1, n, KEPLER_BLOCK
                    j1 = min(n, j0 + KEPLER_BLOCK - 1)
                    mb = d * (j1 - j0 + 1)
                    iw(KW_HAVE_A:KW_HAVE_X) = have0; rw(KR_XSHIFT) = xshift0
                    nf = nf0; ng = ng0
                    do k = 1, nop
                        select case (op(k))
                        case (OP_DRIFT)
                            call stage_add(mb, q(:, j0:j1), v(:, j0:j1), c(k) * h)
                            iw(KW_HAVE_A) = 0; iw(KW_HAVE_G) = 0; iw(KW_HAVE_X) = 0
                        case (OP_KICK)
                            if (iw(KW_HAVE_A) == 0) then
                                if (.not. block_force()) exit
                            end if
                            call stage_add(mb, v(:, j0:j1), w(:, j0:j1, ia), c(k) * h)
                        case (OP_GRAD_KICK)
                            if (iw(KW_HAVE_A) == 0) then
                                if (.not. block_force()) exit
                            end if
                            if (iw(KW_HAVE_G) == 0) then
                                call kepler_field_gradient(d, j1 - j0 + 1, mu, q(:, j0:j1), &
                                                           w(:, j0:j1, ia), w(:, j0:j1, ig))
                                if (.not. fsym_all_finite(mb, w(:, j0:j1, ig))) then
                                    code = FSYM_ERR_NONFINITE_FORCE; exit
                                end if
                                iw(KW_HAVE_G) = 1; ng = ng + 1
                            end if
                            call stage_grad_kick(mb, v(:, j0:j1), w(:, j0:j1, ia), &
                                                 w(:, j0:j1, ig), c(k) * h, u(k) * h**3)
                        case (OP_EXTRAP_KICK)
                            if (iw(KW_HAVE_A) == 0) then
                                if (.not. block_force()) exit
                            end if
                            shift = u(k) * h * h
                            if (iw(KW_HAVE_X) == 0 .or. rw(KR_XSHIFT) /= shift) then
                                call stage_shift(mb, w(:, j0:j1, iqe), q(:, j0:j1), &
                                                 w(:, j0:j1, ia), shift)
                                rw(KR_XSHIFT) = shift
                                call kepler_field(d, j1 - j0 + 1, mu, w(:, j0:j1, iqe), &
                                                  w(:, j0:j1, iae))
                                if (.not. fsym_all_finite(mb, w(:, j0:j1, iae))) then
                                    code = FSYM_ERR_NONFINITE_FORCE; exit
                                end if
                                iw(KW_HAVE_X) = 1; nf = nf + 1
                            end if
                            call stage_add(mb, v(:, j0:j1), w(:, j0:j1, iae), c(k) * h)
                        case default
                            ! nothing else can occur here
                        end select
                    end do
                    if (code /= FSYM_SUCCESS) exit
                    ! the block's new state, while it is in cache
                    if (.not. (fsym_all_finite(mb, q(:, j0:j1)) .and. &
                               fsym_all_finite(mb, v(:, j0:j1)))) then
                        k = nop + 1; code = FSYM_ERR_NONFINITE_STATE; exit
                    end if
                end do
                if (code /= FSYM_SUCCESS) then
                    kfail = istep; stage = k; dnf = nf - nf0; dng = ng - ng0
                    return
                end if
            end do
            dnf = 0; dng = 0
        end subroutine advance

        !> a(q) of the block j0:j1 into SLOT_A, checked and counted; false (and `code` set)
        !> when it is not finite.
        logical function block_force()
            call kepler_field(d, j1 - j0 + 1, mu, q(:, j0:j1), w(:, j0:j1, ia))
            block_force = fsym_all_finite(mb, w(:, j0:j1, ia))
            if (block_force) then
                iw(KW_HAVE_A) = 1; nf = nf + 1
            else
                code = FSYM_ERR_NONFINITE_FORCE
            end if
        end function block_force

    end subroutine kepler_run_blocks

    !> `fsym_kernel_begin` for d = 2 without compensation, in one pass over the bodies on
    !> scalars: the same checks in the same order, the same saved state and cache rule.
    subroutine begin_2d(n, q, v, h, w, nslot, iw, rw, stat)
        integer, intent(in) :: n, nslot
        real(wp), intent(in) :: q(2, n), v(2, n), h
        real(wp), intent(inout) :: w(2, n, nslot)
        integer, intent(inout) :: iw(KERNEL_NIW)
        real(wp), intent(inout) :: rw(KERNEL_NRW)
        integer, intent(out) :: stat
        integer :: j, iq0, iv0, il
        logical :: fin, moved
        if (.not. (h /= 0.0_wp .and. abs(h) <= huge(h))) then
            stat = FSYM_ERR_BAD_STEP; return
        end if
        iq0 = iw(KW_MAP - 1 + SLOT_Q0); iv0 = iw(KW_MAP - 1 + SLOT_V0)
        il = iw(KW_MAP - 1 + SLOT_QLAST)
        fin = .true.; moved = .false.
        do j = 1, n
            fin = fin .and. ieee_is_finite(q(1, j)) .and. ieee_is_finite(q(2, j)) .and. &
                  ieee_is_finite(v(1, j)) .and. ieee_is_finite(v(2, j))
            moved = moved .or. q(1, j) /= w(1, j, il) .or. q(2, j) /= w(2, j, il)
            w(1, j, iq0) = q(1, j); w(2, j, iq0) = q(2, j)
            w(1, j, iv0) = v(1, j); w(2, j, iv0) = v(2, j)
        end do
        if (.not. fin) then
            stat = FSYM_ERR_NONFINITE_STATE; return
        end if
        if (iw(KW_HAVE_A) /= 0 .and. moved) call fsym_kernel_invalidate(iw)
        rw(KR_H) = h
        iw(KW_PC) = 1
        iw(KW_REQ) = REQ_DONE
        iw(KW_ACTIVE) = 1
        stat = FSYM_SUCCESS
    end subroutine begin_2d

    !> The planar scalar path of `fsym_kernel_run_kepler` (entered after `begin_2d`, which
    !> saved the entry state in SLOT_Q0/SLOT_V0). Each body runs all its steps on scalars
    !> (state, forces and cache flags in registers), with the operations of `axpy`, `axpy2`
    !> and `kepler_field`/`kepler_field_gradient` element by element, so bitwise the same.
    !> The bodies are independent, so running them one after the other gives the state of
    !> running them step by step. When a body fails at step kf (the earliest over the
    !> bodies; at equal steps the lowest body, as a step-by-step run finds it first), every
    !> body is brought to the end of step kf - 1: a single body is already there (its
    !> failing step undone on scalars); several bodies run again from the saved entry state.
    subroutine kepler_run_2d(nop, op, c, u, n, q, v, h, mu, nsteps, w, nslot, iw, rw, nf, ng, &
                             ndone, stat)
        integer, intent(in) :: nop, op(nop), n, nslot
        real(wp), intent(in) :: c(nop), u(nop), h, mu
        integer(ik), intent(in) :: nsteps
        real(wp), intent(inout) :: q(2, n), v(2, n), w(2, n, nslot)
        integer, intent(inout) :: iw(KERNEL_NIW)
        real(wp), intent(inout) :: rw(KERNEL_NRW)
        integer(ik), intent(inout) :: nf, ng
        integer(ik), intent(out) :: ndone
        integer, intent(out) :: stat
        ! per body, after its run: a, g, e (force at the shifted point), x (shifted point)
        real(wp) :: fin(8, KEPLER_SCALAR_MAX)
        integer :: j, ia, ig, iqe, iae, hva0, hvg0, hvx0, hva, hvg, hvx, stage, code
        integer :: fstage, fcode
        integer(ik) :: kf, ifail, nfb, ngb, pf, pg, fpf, fpg
        real(wp) :: xs0, xs

        ia = iw(KW_MAP - 1 + SLOT_A); ig = iw(KW_MAP - 1 + SLOT_G)
        iqe = iw(KW_MAP - 1 + SLOT_QE); iae = iw(KW_MAP - 1 + SLOT_AE)
        hva0 = iw(KW_HAVE_A); hvg0 = iw(KW_HAVE_G); hvx0 = iw(KW_HAVE_X)
        xs0 = rw(KR_XSHIFT)
        stat = FSYM_SUCCESS
        kf = nsteps + 1
        fstage = 0; fcode = FSYM_SUCCESS; fpf = 0; fpg = 0
        nfb = nf; ngb = ng
        do j = 1, n
            call body(j, min(nsteps, kf))
            if (ifail > 0 .and. ifail < kf) then
                kf = ifail; fstage = stage; fcode = code; fpf = pf; fpg = pg
            end if
        end do
        if (kf > nsteps) then
            ! every body ran every step: its cache (the same flags for all) stays valid
            do j = 1, n
                w(:, j, ia) = fin(1:2, j)
                if (hvg /= 0) w(:, j, ig) = fin(3:4, j)
                if (hvx /= 0) then
                    w(:, j, iae) = fin(5:6, j); w(:, j, iqe) = fin(7:8, j)
                end if
            end do
            iw(KW_HAVE_A) = hva; iw(KW_HAVE_G) = hvg; iw(KW_HAVE_X) = hvx
            rw(KR_XSHIFT) = xs
            nf = nfb; ng = ngb
            if (hva /= 0) w(:, :, iw(KW_MAP - 1 + SLOT_QLAST)) = q
            ndone = nsteps
        else
            if (n > 1) then
                q = w(:, :, iw(KW_MAP - 1 + SLOT_Q0))
                v = w(:, :, iw(KW_MAP - 1 + SLOT_V0))
                do j = 1, n
                    call body(j, kf - 1)      ! cannot fail: no body failed before step kf
                end do
            end if
            ! counters as a step-by-step run leaves them: through step kf - 1, plus what the
            ! failing step had evaluated when it failed
            nf = nfb + fpf; ng = ngb + fpg
            call fsym_kernel_invalidate(iw)
            iw(KW_PC) = fstage
            stat = fcode
            ndone = kf - 1
        end if
        iw(KW_ACTIVE) = 0
        iw(KW_REQ) = REQ_DONE

    contains

        !> Body j from its state in q, v and the entry cache, for up to `nst` steps. Leaves
        !> the new state in q(:, j), v(:, j), its forces in fin(:, j), flags in hva, hvg,
        !> hvx, xs, counters in nfb, ngb; on failure at step `ifail` (stage `stage`, error
        !> `code`) the state and counters of the start of that step, and in `pf`, `pg` the
        !> evaluations the failing step had made.
        subroutine body(j, nst)
            integer, intent(in) :: j
            integer(ik), intent(in) :: nst
            integer(ik) :: i, nfs, ngs
            integer :: k
            real(wp) :: q1, q2, v1, v2, a1, a2, g1, g2, x1, x2, e1, e2, r2, s, r, t3, shift
            real(wp) :: q1s, q2s, v1s, v2s
            logical :: ht        ! t3 = r2 sqrt(r2) holds for the current q
            ifail = 0; stage = 0; code = FSYM_SUCCESS; pf = 0; pg = 0
            hva = hva0; hvg = hvg0; hvx = hvx0; xs = xs0
            nfb = nf; ngb = ng
            q1 = q(1, j); q2 = q(2, j); v1 = v(1, j); v2 = v(2, j)
            a1 = w(1, j, ia); a2 = w(2, j, ia)
            g1 = 0.0_wp; g2 = 0.0_wp; e1 = 0.0_wp; e2 = 0.0_wp; x1 = 0.0_wp; x2 = 0.0_wp
            if (hvg /= 0) then
                g1 = w(1, j, ig); g2 = w(2, j, ig)
            end if
            if (hvx /= 0) then
                e1 = w(1, j, iae); e2 = w(2, j, iae); x1 = w(1, j, iqe); x2 = w(2, j, iqe)
            end if
            ht = .false.; t3 = 0.0_wp
            steps: do i = 1, nst
                q1s = q1; q2s = q2; v1s = v1; v2s = v2; nfs = nfb; ngs = ngb
                do k = 1, nop
                    if (op(k) /= OP_DRIFT .and. hva == 0) then
                        ! every kind of kick needs a(q) first
                        if (.not. planar_force(mu, q1, q2, a1, a2, t3)) then
                            code = FSYM_ERR_NONFINITE_FORCE; exit steps
                        end if
                        ht = .true.; hva = 1; nfb = nfb + 1
                    end if
                    select case (op(k))
                    case (OP_DRIFT)
                        s = c(k) * h
                        q1 = axpy(q1, s, v1)
                        q2 = axpy(q2, s, v2)
                        hva = 0; hvg = 0; hvx = 0; ht = .false.
                    case (OP_KICK)
                        s = c(k) * h
                        v1 = axpy(v1, s, a1)
                        v2 = axpy(v2, s, a2)
                    case (OP_GRAD_KICK)
                        if (hvg == 0) then
                            if (.not. ht) then
                                r2 = q1**2 + q2**2
                                t3 = r2 * sqrt(r2)
                            end if
                            s = 4.0_wp * mu / t3
                            g1 = s * a1
                            g2 = s * a2
                            if (.not. (ieee_is_finite(g1) .and. ieee_is_finite(g2))) then
                                code = FSYM_ERR_NONFINITE_FORCE; exit steps
                            end if
                            hvg = 1; ngb = ngb + 1
                        end if
                        s = c(k) * h
                        r = u(k) * h**3
                        v1 = axpy2(v1, s, a1, r, g1)
                        v2 = axpy2(v2, s, a2, r, g2)
                    case (OP_EXTRAP_KICK)
                        shift = u(k) * h * h
                        if (hvx == 0 .or. xs /= shift) then
                            x1 = axpy(q1, shift, a1)
                            x2 = axpy(q2, shift, a2)
                            xs = shift
                            if (.not. planar_force(mu, x1, x2, e1, e2, r)) then
                                code = FSYM_ERR_NONFINITE_FORCE; exit steps
                            end if
                            hvx = 1; nfb = nfb + 1
                        end if
                        s = c(k) * h
                        v1 = axpy(v1, s, e1)
                        v2 = axpy(v2, s, e2)
                    case default
                        continue      ! a validated scheme has no other op codes
                    end select
                end do
                if (.not. (ieee_is_finite(q1) .and. ieee_is_finite(q2) .and. &
                           ieee_is_finite(v1) .and. ieee_is_finite(v2))) then
                    k = nop + 1; code = FSYM_ERR_NONFINITE_STATE; exit steps
                end if
            end do steps
            if (code /= FSYM_SUCCESS) then
                ifail = i; stage = k; pf = nfb - nfs; pg = ngb - ngs
                q1 = q1s; q2 = q2s; v1 = v1s; v2 = v2s
                nfb = nfs; ngb = ngs
            end if
            q(1, j) = q1; q(2, j) = q2; v(1, j) = v1; v(2, j) = v2
            fin(:, j) = [a1, a2, g1, g2, e1, e2, x1, x2]
        end subroutine body

    end subroutine kepler_run_2d

    !> Planar Kepler force (f1, f2) = -mu x/|x|^3 with the operations of `kepler_field`, and
    !> t3 = |x|^3 (r2 sqrt(r2), which the gradient term reuses); false when not finite.
    logical function planar_force(mu, x1, x2, f1, f2, t3)
        real(wp), intent(in) :: mu, x1, x2
        real(wp), intent(out) :: f1, f2, t3
        real(wp) :: r2, s
        r2 = x1**2 + x2**2
        t3 = r2 * sqrt(r2)
        s = -mu / t3
        f1 = s * x1
        f2 = s * x2
        planar_force = ieee_is_finite(f1) .and. ieee_is_finite(f2)
    end function planar_force

    ! ---------------------------------------------------------------- stage arithmetic
    ! Every update of the state is `axpy` or `axpy2`: the array stages below apply them
    ! element-wise, the planar Kepler path (kepler_run_2d) to scalars.

    !> The update of every drift, kick and shift: x + s y.
    elemental real(wp) function axpy(x, s, y)
        real(wp), intent(in) :: x, s, y
        axpy = x + s * y
    end function axpy

    !> The update of a gradient kick: x + (s y + r z).
    elemental real(wp) function axpy2(x, s, y, r, z)
        real(wp), intent(in) :: x, s, y, r, z
        axpy2 = x + (s * y + r * z)
    end function axpy2

    !> Drift q <- q + s v or kick v <- v + s a (s = c h): x <- x + s y.
    pure subroutine stage_add(m, x, y, s)
        integer, intent(in) :: m
        real(wp), intent(inout) :: x(m)
        real(wp), intent(in) :: y(m), s
        x = axpy(x, s, y)
    end subroutine stage_add

    !> Gradient kick v <- v + (s a + r g) (s = c h, r = u h^3).
    pure subroutine stage_grad_kick(m, v, a, g, s, r)
        integer, intent(in) :: m
        real(wp), intent(inout) :: v(m)
        real(wp), intent(in) :: a(m), g(m), s, r
        v = axpy2(v, s, a, r, g)
    end subroutine stage_grad_kick

    !> Extrapolated point x <- q + s a (s = u h^2).
    pure subroutine stage_shift(m, x, q, a, s)
        integer, intent(in) :: m
        real(wp), intent(out) :: x(m)
        real(wp), intent(in) :: q(m), a(m), s
        x = axpy(q, s, a)
    end subroutine stage_shift

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
