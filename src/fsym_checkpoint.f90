!> Checkpoint and restart: the complete state of a splitting integration as one flat array
!> of doubles with a version tag, the same for every face (modern, F77, reverse
!> communication, C), so that a run resumed from it is bitwise identical to an
!> uninterrupted one, compensated runs included.
!>
!> What it holds: positions and velocities, the clock (time as t_base + k h_now and the
!> step count), the evaluation counters, the method (op codes, coefficients c and u), the
!> kernel's state (cached forces and which are valid, the shift of the cached extrapolated
!> force, the compensation terms) and its whole work array. Integers are stored as doubles
!> (exact below 2**53). The force model's own parameters (masses, couplings) are the
!> caller's and are not in it.
!>
!>     ck(1)  CKPT_TAG           ck(2)  CKPT_VERSION        ck(3)  length of ck
!>     ck(4:7)  d, n, nop, nslot          ck(8:11)  comp, have_a, have_g, have_x
!>     ck(12:13) nf, ng          ck(14:16) steps, k_since (steps at h_now), 0 (reserved)
!>     ck(17:20) t_base, h_now, h of the last step, xshift
!>     ck(21:31) slots ia, ig, iqe, iae, iq0, iv0, iqlast, iqc, ivc, iqc0, ivc0 (iq0 and
!>               iqlast may come in either order: the kernel swaps their roles)
!>     ck(CKPT_HEADER+1:) op(nop), c(nop), u(nop), q(d,n), v(d,n), w(d,n,nslot)
module fsym_checkpoint
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_CHECKPOINT
    use fsym_kernel, only: kernel_state_t
    implicit none
    private

    real(wp), parameter, public :: CKPT_TAG = 5146735.0_wp   !! ck(1) of every checkpoint
    integer, parameter, public :: CKPT_VERSION = 1           !! ck(2): layout version
    integer, parameter, public :: CKPT_HEADER = 31           !! header length

    !> The clock and step count of a stepper, as a checkpoint keeps them.
    type, public :: ckpt_clock_t
        real(wp) :: t_base = 0.0_wp     !! time when the step size last changed
        real(wp) :: h_now = 0.0_wp      !! current step size
        integer(ik) :: k_since = 0      !! steps since then
        integer(ik) :: steps = 0        !! steps since init
    end type ckpt_clock_t

    public :: fsym_checkpoint_length, fsym_checkpoint_pack, fsym_checkpoint_unpack

contains

    !> Length of the checkpoint of a method of `nop` stages on (d, n) with `nslot` slots,
    !> as a 64-bit integer (it can exceed a default integer for huge n).
    pure integer(ik) function fsym_checkpoint_length(nop, d, n, nslot) result(m)
        integer, intent(in) :: nop, d, n, nslot   !! stages, dimensions, bodies, slots
        m = CKPT_HEADER + 3_ik * nop + int(d, ik) * n * (2 + nslot)
    end function fsym_checkpoint_length

    !> Write the state into `ck` (at least `fsym_checkpoint_length` long).
    pure subroutine fsym_checkpoint_pack(op, c, u, ks, clock, q, v, w, ck)
        integer, intent(in) :: op(:)                            !! op codes
        real(wp), intent(in) :: c(:), u(:)                      !! coefficients
        type(kernel_state_t), intent(in) :: ks                  !! kernel state (between steps)
        type(ckpt_clock_t), intent(in) :: clock                 !! clock and step count
        real(wp), intent(in) :: q(ks%d * ks%n), v(ks%d * ks%n)  !! state
        real(wp), intent(in) :: w(ks%d * ks%n * ks%nslot)       !! kernel work array
        real(wp), intent(out) :: ck(:)                          !! the checkpoint
        integer(ik) :: k, m, nop
        nop = size(op); m = int(ks%d, ik) * ks%n
        ck(1:CKPT_HEADER) = [CKPT_TAG, real(CKPT_VERSION, wp), &
            real(fsym_checkpoint_length(size(op), ks%d, ks%n, ks%nslot), wp), &
            real(ks%d, wp), real(ks%n, wp), real(nop, wp), real(ks%nslot, wp), &
            flag(ks%comp), flag(ks%have_a), flag(ks%have_g), flag(ks%have_x), &
            real(ks%nf, wp), real(ks%ng, wp), real(clock%steps, wp), real(clock%k_since, wp), &
            0.0_wp, clock%t_base, clock%h_now, ks%h, ks%xshift, &
            real([ks%ia, ks%ig, ks%iqe, ks%iae, ks%iq0, ks%iv0, ks%iqlast, ks%iqc, ks%ivc, &
                  ks%iqc0, ks%ivc0], wp)]
        k = CKPT_HEADER
        ck(k + 1:k + nop) = real(op, wp); k = k + nop
        ck(k + 1:k + nop) = c; k = k + nop
        ck(k + 1:k + nop) = u; k = k + nop
        ck(k + 1:k + m) = q; k = k + m
        ck(k + 1:k + m) = v; k = k + m
        ck(k + 1:k + m * ks%nslot) = w
    end subroutine fsym_checkpoint_pack

    !> Read a checkpoint into the state of an integrator set up for the same method on the
    !> same arrays (`ks` as its set-up made it: the layout is checked against it). On any
    !> mismatch (tag, version, length, shape, method, layout, a corrupt flag or count)
    !> `stat` = FSYM_ERR_CHECKPOINT, `msg` says what, and nothing is changed.
    pure subroutine fsym_checkpoint_unpack(ck, op, c, u, ks, clock, q, v, w, stat, msg)
        real(wp), intent(in) :: ck(:)                              !! the checkpoint
        integer, intent(in) :: op(:)                               !! the integrator's op codes
        real(wp), intent(in) :: c(:), u(:)                         !! and coefficients
        type(kernel_state_t), intent(inout) :: ks                  !! kernel state
        type(ckpt_clock_t), intent(out) :: clock                   !! clock and step count
        real(wp), intent(inout) :: q(ks%d * ks%n), v(ks%d * ks%n)  !! state
        real(wp), intent(inout) :: w(ks%d * ks%n * ks%nslot)       !! kernel work array
        integer, intent(out) :: stat                               !! status
        character(len=*), intent(inout) :: msg                     !! what did not fit
        integer(ik) :: k, m, nop, total
        stat = FSYM_ERR_CHECKPOINT
        nop = size(op); m = int(ks%d, ik) * ks%n
        total = fsym_checkpoint_length(size(op), ks%d, ks%n, ks%nslot)
        if (size(ck, kind=ik) < CKPT_HEADER) then
            msg = 'checkpoint shorter than its header'; return
        end if
        if (ck(1) /= CKPT_TAG .or. ck(2) /= real(CKPT_VERSION, wp)) then
            msg = 'not a forward-symplectic checkpoint of version 1'; return
        end if
        if (ck(3) /= real(total, wp) .or. size(ck, kind=ik) < total) then
            msg = 'checkpoint length does not fit this integrator'; return
        end if
        if (any(ck(4:7) /= real([ks%d, ks%n, int(nop), ks%nslot], wp))) then
            msg = 'checkpoint of other dimensions, bodies, method or layout'; return
        end if
        if (ck(8) /= flag(ks%comp)) then
            msg = 'checkpoint compensated and integrator not, or the reverse'; return
        end if
        ! slots iq0 and iqlast trade roles in the kernel: either order fits
        if (any(ck([21, 22, 23, 24, 26, 28, 29, 30, 31]) /= real([ks%ia, ks%ig, ks%iqe, &
                ks%iae, ks%iv0, ks%iqc, ks%ivc, ks%iqc0, ks%ivc0], wp)) .or. .not. &
                (all(ck([25, 27]) == real([ks%iq0, ks%iqlast], wp)) .or. &
                 all(ck([25, 27]) == real([ks%iqlast, ks%iq0], wp)))) then
            msg = 'checkpoint of another work-array layout'; return
        end if
        k = CKPT_HEADER
        if (any(ck(k + 1:k + nop) /= real(op, wp)) .or. any(ck(k + nop + 1:k + 2 * nop) /= c) &
            .or. any(ck(k + 2 * nop + 1:k + 3 * nop) /= u)) then
            msg = 'checkpoint of another method (op codes or coefficients differ)'; return
        end if
        if (.not. (all(ck(9:11) == 0.0_wp .or. ck(9:11) == 1.0_wp) .and. &
                   all(ck(12:15) >= 0.0_wp .and. ck(12:15) < 2.0_wp**53) .and. &
                   ck(15) <= ck(14))) then
            msg = 'corrupt checkpoint (flags or counters out of range)'; return
        end if
        ks%have_a = ck(9) == 1.0_wp; ks%have_g = ck(10) == 1.0_wp; ks%have_x = ck(11) == 1.0_wp
        ks%nf = int(ck(12), ik); ks%ng = int(ck(13), ik)
        clock%steps = int(ck(14), ik); clock%k_since = int(ck(15), ik)
        clock%t_base = ck(17); clock%h_now = ck(18); ks%h = ck(19); ks%xshift = ck(20)
        ks%active = .false.; ks%pc = 0; ks%req = 0
        ks%iq0 = nint(ck(25)); ks%iqlast = nint(ck(27))
        k = k + 3 * nop
        q = ck(k + 1:k + m); k = k + m
        v = ck(k + 1:k + m); k = k + m
        w = ck(k + 1:k + m * ks%nslot)
        stat = FSYM_SUCCESS
    end subroutine fsym_checkpoint_unpack

    pure real(wp) function flag(x)
        logical, intent(in) :: x
        flag = merge(1.0_wp, 0.0_wp, x)
    end function flag

end module fsym_checkpoint
