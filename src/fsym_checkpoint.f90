!> Checkpoint and restart: the complete state of a splitting integration as one flat array
!> of doubles, the same for every face (modern, F77, reverse communication, C), so that a run
!> resumed from it is bitwise identical to an uninterrupted one, compensated runs included.
!>
!> What it holds: positions and velocities, the clock (time as t_base + k h_now and the
!> step count), the method (op codes, coefficients c and u), the kernel's state as the kernel
!> packs it (`fsym_kernel_pack`: cached forces and which are valid, counters, compensation)
!> and its whole work array, and a CRC-32 of all of it. Integers are stored as doubles (exact
!> below 2**53). The force model's own parameters (masses, couplings) are the caller's and
!> are not in it. Format version 2:
!>
!>     ck(1)  CKPT_TAG      ck(2)  CKPT_VERSION (2)      ck(3)  length of ck
!>     ck(4:7)  d, n, nop, nslot       ck(8:11)  steps, k_since, t_base, h_now
!>     ck(12:29)  the kernel state (`KERNEL_NPACK` reals)
!>     ck(30:)  op(nop), c(nop), u(nop), q(d,n), v(d,n), w(d,n,nslot)
!>     ck(length)  CRC-32 (IEEE 802.3) of the bytes of ck(1:length-1)
!>
!> Version 1 (before the kernel was sealed: no checksum, the kernel's fields and slot roles in
!> a header of 31) is still read, into the same state, and resumes bitwise.
module fsym_checkpoint
    use, intrinsic :: iso_fortran_env, only: int64
    use fsym_kinds, only: wp, ik, fsym_same
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_CHECKPOINT
    use fsym_kernel, only: kernel_state_t, KERNEL_NPACK, KERNEL_PACK_TAG, fsym_kernel_pack, &
                           fsym_kernel_unpack, fsym_kernel_slots, fsym_kernel_point_slots
    implicit none
    private

    real(wp), parameter, public :: CKPT_TAG = 5146735.0_wp   !! ck(1) of every checkpoint
    integer, parameter, public :: CKPT_VERSION = 2           !! ck(2): layout version
    integer, parameter, public :: CKPT_HEADER = 11 + KERNEL_NPACK  !! header length
    integer, parameter :: V1_HEADER = 31

    !> The clock and step count of a stepper, as a checkpoint keeps them.
    type, public :: ckpt_clock_t
        real(wp) :: t_base = 0.0_wp     !! time when the step size last changed
        real(wp) :: h_now = 0.0_wp      !! current step size
        integer(ik) :: k_since = 0      !! steps since then
        integer(ik) :: steps = 0        !! steps since init
    end type ckpt_clock_t

    public :: fsym_checkpoint_length, fsym_checkpoint_pack, fsym_checkpoint_unpack
    public :: fsym_crc32, fsym_crc32_table, fsym_crc32_feed
    integer(int64), parameter, public :: CRC_ONES = int(z'FFFFFFFF', int64)
        !! start and final xor of a CRC-32

contains

    !> Length of the checkpoint of a method of `nop` stages on (d, n) with `nslot` slots,
    !> as a 64-bit integer (it can exceed a default integer for huge n).
    pure integer(ik) function fsym_checkpoint_length(nop, d, n, nslot) result(m)
        integer, intent(in) :: nop, d, n, nslot   !! stages, dimensions, bodies, slots
        m = CKPT_HEADER + 3_ik * nop + int(d, ik) * n * (2 + nslot) + 1
    end function fsym_checkpoint_length

    !> Write the state into `ck` (at least `fsym_checkpoint_length` long; the rest is left).
    pure subroutine fsym_checkpoint_pack(op, c, u, ks, clock, q, v, w, ck)
        integer, intent(in) :: op(:)                  !! op codes
        real(wp), intent(in) :: c(:), u(:)            !! coefficients
        type(kernel_state_t), intent(in) :: ks        !! kernel state (between steps)
        type(ckpt_clock_t), intent(in) :: clock       !! clock and step count
        real(wp), intent(in) :: q(:, :), v(:, :)      !! state (d, n)
        real(wp), intent(in) :: w(:)                  !! kernel work array (d*n*nslot)
        real(wp), intent(inout) :: ck(:)              !! the checkpoint
        integer(ik) :: k, m, nop, total
        nop = size(op); m = size(q, kind=ik)
        total = fsym_checkpoint_length(size(op), size(q, 1), size(q, 2), fsym_kernel_slots(ks))
        ck(1:11) = [CKPT_TAG, real(CKPT_VERSION, wp), real(total, wp), &
                    real(size(q, 1), wp), real(size(q, 2), wp), real(nop, wp), &
                    real(fsym_kernel_slots(ks), wp), real(clock%steps, wp), &
                    real(clock%k_since, wp), clock%t_base, clock%h_now]
        call fsym_kernel_pack(ks, ck(12:CKPT_HEADER))
        k = CKPT_HEADER
        ck(k + 1:k + nop) = real(op, wp); k = k + nop
        ck(k + 1:k + nop) = c; k = k + nop
        ck(k + 1:k + nop) = u; k = k + nop
        ck(k + 1:k + m) = reshape(q, [m]); k = k + m
        ck(k + 1:k + m) = reshape(v, [m]); k = k + m
        ck(k + 1:total - 1) = w(1:total - 1 - k)
        ck(total) = real(fsym_crc32(ck(1:total - 1)), wp)
    end subroutine fsym_checkpoint_pack

    !> Read a checkpoint into the state of an integrator set up for the same method on the
    !> same arrays (`ks` as its set-up made it: the layout is checked against it). On any
    !> mismatch `stat` = FSYM_ERR_CHECKPOINT, `msg` says which check failed (tag, version,
    !> length, checksum, shape, method, kernel state), and nothing is changed.
    pure subroutine fsym_checkpoint_unpack(ck, op, c, u, ks, clock, q, v, w, stat, msg)
        real(wp), intent(in) :: ck(:)                    !! the checkpoint
        integer, intent(in) :: op(:)                     !! the integrator's op codes
        real(wp), intent(in) :: c(:), u(:)               !! and coefficients
        type(kernel_state_t), intent(inout) :: ks        !! kernel state
        type(ckpt_clock_t), intent(out) :: clock         !! clock and step count
        real(wp), intent(inout) :: q(:, :), v(:, :)      !! state (d, n)
        real(wp), intent(inout) :: w(:)                  !! kernel work array (d*n*nslot)
        integer, intent(out) :: stat                     !! status
        character(len=*), intent(inout) :: msg           !! what did not fit
        type(kernel_state_t) :: kn
        real(wp) :: r(KERNEL_NPACK)
        integer(ik) :: k, m, nop, total, head, mw
        integer :: d, n, nslot, iq0, iqlast
        stat = FSYM_ERR_CHECKPOINT
        nop = size(op); d = size(q, 1); n = size(q, 2); m = int(d, ik) * n
        nslot = fsym_kernel_slots(ks); mw = m * nslot
        if (size(ck, kind=ik) < V1_HEADER) then
            msg = 'checkpoint: shorter than its header (truncated?)'; return
        end if
        if (.not. fsym_same(ck(1), CKPT_TAG)) then
            msg = 'checkpoint: not a forward-symplectic checkpoint (tag)'; return
        end if
        if (fsym_same(ck(2), 2.0_wp)) then
            head = CKPT_HEADER; total = fsym_checkpoint_length(size(op), d, n, nslot)
        else if (fsym_same(ck(2), 1.0_wp)) then
            head = V1_HEADER; total = fsym_checkpoint_length(size(op), d, n, nslot) - 1 - &
                                       CKPT_HEADER + V1_HEADER
        else
            msg = 'checkpoint: format version is neither 1 nor 2'; return
        end if
        if (.not. (fsym_same(ck(4), real(d, wp)) .and. fsym_same(ck(5), real(n, wp)))) then
            msg = 'checkpoint: of other dimensions or number of bodies than this integrator'
            return
        end if
        if (.not. (fsym_same(ck(6), real(nop, wp)) .and. fsym_same(ck(7), real(nslot, wp)))) then
            msg = 'checkpoint: of another method (stages or work slots differ)'; return
        end if
        if (.not. fsym_same(ck(3), real(total, wp)) .or. size(ck, kind=ik) < total) then
            msg = 'checkpoint: length does not fit (truncated or of another method)'; return
        end if
        if (head == CKPT_HEADER) then
            if (.not. fsym_same(ck(total), real(fsym_crc32(ck(1:total - 1)), wp))) then
                msg = 'checkpoint: checksum (CRC-32) does not match: the file is corrupt'
                return
            end if
        end if
        k = head
        if (.not. (all(fsym_same(ck(k + 1:k + nop), real(op, wp))) .and. &
                   all(fsym_same(ck(k + nop + 1:k + 2 * nop), c)) .and. &
                   all(fsym_same(ck(k + 2 * nop + 1:k + 3 * nop), u)))) then
            msg = 'checkpoint: of another method (op codes or coefficients differ)'; return
        end if
        if (head == CKPT_HEADER) then
            if (.not. (all(ck(8:9) >= 0.0_wp .and. ck(8:9) < 2.0_wp**53) .and. &
                       ck(9) <= ck(8))) then
                msg = 'checkpoint: step counters out of range'; return
            end if
            r = ck(12:CKPT_HEADER)
            clock%steps = int(ck(8), ik); clock%k_since = int(ck(9), ik)
            clock%t_base = ck(10); clock%h_now = ck(11)
        else
            ! version 1: the kernel's fields one by one, slots iq0 and iqlast in either order
            if (.not. (all(ck(14:15) >= 0.0_wp .and. ck(14:15) < 2.0_wp**53) .and. &
                       ck(15) <= ck(14))) then
                msg = 'checkpoint: step counters out of range'; return
            end if
            r = [ck(19), ck(20), ck(12), ck(13), ck(4), ck(5), ck(7), ck(8), ck(9), ck(10), &
                 ck(11), 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, ck(6), KERNEL_PACK_TAG]
            clock%steps = int(ck(14), ik); clock%k_since = int(ck(15), ik)
            clock%t_base = ck(17); clock%h_now = ck(18)
        end if
        kn = ks
        call fsym_kernel_unpack(r, kn, stat, msg)
        if (stat /= FSYM_SUCCESS) return
        k = head + 3 * nop
        if (head == V1_HEADER) then
            call fsym_kernel_point_slots(ks, iq0, iqlast)
            if (.not. (nint(ck(25)) == iq0 .and. nint(ck(27)) == iqlast .or. &
                       nint(ck(25)) == iqlast .and. nint(ck(27)) == iq0)) then
                stat = FSYM_ERR_CHECKPOINT
                msg = 'checkpoint: version 1 of another work-array layout'; return
            end if
        end if
        q = reshape(ck(k + 1:k + m), [d, n]); k = k + m
        v = reshape(ck(k + 1:k + m), [d, n]); k = k + m
        w(1:mw) = ck(k + 1:k + mw)
        if (head == V1_HEADER) then     ! the cached force's point into the slot it has now
            w((iqlast - 1) * m + 1:iqlast * m) = ck(k + (nint(ck(27)) - 1) * m + 1: &
                                                   k + nint(ck(27)) * m)
        end if
        ks = kn
    end subroutine fsym_checkpoint_unpack

    !> CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320) of the bytes of x, low byte of
    !> each value first, as a non-negative integer below 2**32.
    pure integer(int64) function fsym_crc32(x) result(crc)
        real(wp), intent(in) :: x(:)   !! the values
        integer(int64) :: table(0:255), word
        integer(ik) :: i
        table = fsym_crc32_table()
        crc = CRC_ONES
        do i = 1, size(x, kind=ik)
            crc = fsym_crc32_feed(crc, transfer(x(i), word), 8, table)
        end do
        crc = ieor(crc, CRC_ONES)
    end function fsym_crc32

    !> The byte table of CRC-32 (reflected polynomial 0xEDB88320), for `fsym_crc32_feed`.
    pure function fsym_crc32_table() result(table)
        integer(int64) :: table(0:255)     !! CRC of each byte value
        integer(int64), parameter :: poly = int(z'EDB88320', int64)
        integer(int64) :: t
        integer :: j, b
        do j = 0, 255
            t = j
            do b = 1, 8
                if (btest(t, 0)) then
                    t = ieor(shiftr(t, 1), poly)
                else
                    t = shiftr(t, 1)
                end if
            end do
            table(j) = t
        end do
    end function fsym_crc32_table

    !> A running CRC-32 (started at 2**32 - 1, finished by xor with it) after the `nbytes`
    !> low bytes of `word`, low byte first.
    pure integer(int64) function fsym_crc32_feed(crc, word, nbytes, table) result(c)
        integer(int64), intent(in) :: crc            !! running CRC
        integer(int64), intent(in) :: word           !! the bytes
        integer, intent(in) :: nbytes                !! how many (1 to 8)
        integer(int64), intent(in) :: table(0:255)   !! from `fsym_crc32_table`
        integer :: b
        c = crc
        do b = 0, 8 * nbytes - 8, 8
            c = ieor(table(iand(ieor(c, shiftr(word, b)), 255_int64)), shiftr(c, 8))
        end do
    end function fsym_crc32_feed

end module fsym_checkpoint
