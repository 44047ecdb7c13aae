!> The planetary drop-in for heliocentric legacy codes (Mercury, SWIFT and their kin): what
!> the F77 routines FSYMPW, FSYMPI, FSYMPL, FSYMPU, FSYMPX, FSYMPM, FSYMPE and the C functions
!> `fsym_planets_*` share. The caller keeps what such a code holds (central mass M0, G, the
!> masses M(N), heliocentric positions X(3,N) and velocities V(3,N)); a call advances it by
!> NSTEP steps of `planets_model_t` (the Wisdom-Holman splitting, Jacobi or democratic
!> heliocentric coordinates) under the one kernel, exactly as `integrator_t%run_steps` on
!> that model does (bit for bit); for a processed label (`WH+C17`, `WHK-L+C17`, ...: a
!> kernel with a symplectic corrector, module `fsym_processed`) exactly as `processed_t`
!> does: the in-map where a new state is taken, the kernel on the mapped state, the out-map
!> on a copy where the heliocentric state is handed back. Everything lives in the caller's
!> work arrays RW and IW: no SAVE, no COMMON, no module variable, so the routines are
!> reentrant, and RW and IW (with nothing else) are a checkpoint.
!>
!> Layout (N bodies, NOP stages, NSLOT kernel slots of the method; LABEL_MAX = 64):
!>
!>     IW(1) magic   IW(2) N   IW(3) ICOORD (1 Jacobi, 2 democratic, 3 Jacobi eta_k)
!>     IW(4) NOP
!>     IW(5) NSLOT   IW(6) length of the label   IW(7) steps done by the last call
!>     IW(8) status of the last call   IW(9), IW(10) the pair of the last encounter (or the
!>     body whose mass differs: IW(9); 0 the centre, -1 G)   IW(11) body of a failed Kepler
!>     solve   IW(12) busy (1 while the caller's force routine runs)
!>     IW(13:76) the label (character codes)   IW(77:76+NOP) the kernel's op codes
!>     IW(77+NOP) the corrector's order (0: none)
!>     IW(78+NOP) CRC-32 of every other word of IW and of RW(19:29+N+2 NOP)
!>     IW(79+NOP) guard word                                      LIW = 79 + NOP
!>
!>     RW(1:18) the kernel state (packed)   RW(19) M0  RW(20) G  RW(21) HILL
!>     RW(22) the method's stability limit x* (the guard)   RW(23) steps since set-up
!>     RW(24:29) centre of mass and its velocity   RW(30:29+N) the masses
!>     then C(NOP), U(NOP), HM (the step the corrector mapped the state with), the state
!>     Q(3,N), VS(3,N) in the model's coordinates (the mapped state with a corrector), the
!>     heliocentric XL(3,N), VL(3,N) last returned, and the kernel's slots W(3,N,NSLOT):
!>                                    LRW = 30 + 13 N + 2 NOP + 3 N NSLOT
!>
!> NOP and NSLOT are those of the kernel (3 stages for WH, WHK-M, WHK-L, T2 with or
!> without a corrector); the corrector's stages are rebuilt from its order by
!> `fsym_processed_maps` and its work (slots and the output copy, 3 N (NSLOT' + 2) reals)
!> is scratch of the call, like the coordinate conversion.
!>
!> A call whose X, V are bitwise the XL, VL of the last call (and, with a corrector, whose H
!> is bitwise HM) goes on from Q, VS (so that calls of n1 and n2 steps give bitwise the run
!> of n1 + n2 steps); other X, V (a new start, or a state the host changed after an
!> encounter) are converted (and mapped) afresh.
module fsym_legacy_planets
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use fsym_kinds, only: wp, ik, fsym_same
    use fsym_status
    use fsym_scheme, only: scheme_t, OP_GRAD_KICK
    use fsym_force, only: force_model_t
    use fsym_kernel, only: kernel_state_t, fsym_kernel_layout, fsym_kernel_slots, &
                           fsym_kernel_run, fsym_kernel_pack, fsym_kernel_unpack, &
                           fsym_kernel_invalidate, KERNEL_NPACK
    use fsym_guard, only: guard_t, fsym_guard_run
    use fsym_oscillator, only: fsym_stability_interval
    use fsym_checkpoint, only: fsym_crc32_table, fsym_crc32_feed, CRC_ONES
    use fsym_integrator, only: fsym_overlap
    use fsym_planets, only: planets_model_t, planets_helio_to_bary, planets_bary_to_helio, &
                            planets_jacobi_to_bary, PLANETS_JACOBI, PLANETS_KEPLER_WH, &
                            PLANETS_KEPLER_ETA
    use fsym_processed, only: fsym_processed_lookup, fsym_processed_maps, FSYM_MAP_MAX
    implicit none
    private

    public :: pl_sizes, pl_setup, pl_steps, pl_state, pl_message, pl_energy, pl_check
    public :: fsym_pl_force

    abstract interface
        !> The F77 caller's extra force (FSYMPU): accelerations AH(3,N) at the heliocentric
        !> positions XH(3,N), with the caller's data RPAR, IPAR; IERR /= 0 reports a failure
        !> (the step is undone, INFO = FSYM_ERR_MODEL). Added to the N-body interaction.
        subroutine fsym_pl_force(N, XH, AH, RPAR, IPAR, IERR)
            import :: wp
            implicit none
            integer, intent(in) :: N                      !! bodies besides the centre
            real(wp), intent(in) :: XH(3, N)              !! heliocentric positions
            real(wp), intent(out) :: AH(3, N)             !! extra accelerations
            real(wp), intent(inout) :: RPAR(*)            !! the caller's real data
            integer, intent(inout) :: IPAR(*)             !! the caller's integer data
            integer, intent(inout) :: IERR                !! 0 on entry; non-zero = failure
        end subroutine fsym_pl_force
    end interface

    !> The F77 caller's extra force as a force model (FSYMPU): UFORCE with RPAR, IPAR.
    type, extends(force_model_t), public :: pl_f77_force_t
        procedure(fsym_pl_force), pointer, nopass :: f => null()   !! UFORCE
        real(wp), pointer, contiguous :: rpar(:) => null()        !! RPAR
        integer, pointer, contiguous :: ipar(:) => null()         !! IPAR
    contains
        procedure :: acceleration => pl_f77_acceleration          !! calls UFORCE
    end type pl_f77_force_t

    integer, parameter, public :: PL_LABEL_MAX = 64          !! longest method label
    integer, parameter, public :: PL_MAGIC = 20261129        !! IW(1) of a set-up image
    integer, parameter, public :: PL_GUARD = 1886154860      !! last word of a set-up IW
    integer, parameter, public :: PL_IOP = 13 + PL_LABEL_MAX !! IW index of the op codes
    integer, parameter, public :: PL_RM = 30                 !! RW index of the masses
    integer, parameter, public :: PL_MSG_LEN = 200           !! length of a message
    !> ICOORD of Jacobi coordinates with the Kepler masses M_k = eta_k (PLANETS_KEPLER_ETA,
    !> REBOUND's WHFast choice); 1 is Jacobi with M_k = m0 eta_k / eta_(k-1), 2 democratic.
    integer, parameter, public :: PL_JACOBI_ETA = 3

    !> `planets_model_t` with the interaction's local frequency for the step-size guard:
    !> the largest 2 G (m_i + m_j) / r_ij^3 over the pairs of bodies (the Kepler part is
    !> solved exactly and needs no guard).
    type, extends(planets_model_t) :: pl_model_t
        logical :: guarded = .false.
        real(wp), allocatable :: xi(:, :)    ! inertial positions (3, 0:n)
    contains
        procedure :: local_frequency => pl_frequency
        procedure :: has_frequency => pl_has_frequency
    end type pl_model_t

contains

    !> The one place where a method label becomes a stage table for the planetary drop-in
    !> (its F77 and C routines all come here, through `pl_sizes` and `pl_setup`): a kernel
    !> label of `fsym_scheme_by_name`, or a processed label `<kernel>+C<order>` of
    !> `fsym_processed_lookup` (`WH+C17`, `WHK-L+C17`, `WHK-M+C17`, `T2+C5`); `order` is the
    !> corrector's order (0: none), kept in IW.
    subroutine resolve_method(label, s, order, info, msg)
        character(len=*), intent(in) :: label
        type(scheme_t), intent(inout) :: s
        integer, intent(out) :: order
        integer, intent(out) :: info
        character(len=*), intent(inout) :: msg
        order = 0
        if (len_trim(label) > PL_LABEL_MAX) then
            info = FSYM_ERR_BAD_ARGUMENT
            msg = 'planets: the method label is longer than '//fsym_int_text(PL_LABEL_MAX)// &
                  ' characters'
            return
        end if
        call fsym_processed_lookup(label, s, order, info, msg)
    end subroutine resolve_method

    !> Work sizes of the method `label` for n bodies: LRW = 30 + 13 n + 2 NOP + 3 n NSLOT,
    !> LIW = 79 + NOP (NOP stages of the kernel, 3 for a processed label; NSLOT = 4, + 1
    !> with gradient kicks, + 2 with extrapolated ones). Lengths beyond a default integer:
    !> FSYM_ERR_WORK_SIZE.
    subroutine pl_sizes(label, n, lrw, liw, info, msg)
        character(len=*), intent(in) :: label         !! method label
        integer, intent(in) :: n                      !! bodies besides the centre
        integer, intent(out) :: lrw, liw              !! lengths needed
        integer, intent(out) :: info                  !! status
        character(len=*), intent(inout) :: msg        !! message on error
        type(scheme_t) :: s
        type(kernel_state_t) :: ks
        integer(ik) :: r
        integer :: order
        lrw = 0; liw = 0
        call resolve_method(label, s, order, info, msg)
        if (info /= FSYM_SUCCESS) return
        if (n < 1) then
            info = FSYM_ERR_SHAPE; msg = 'planets: need N >= 1 bodies besides the centre'
            return
        end if
        call fsym_kernel_layout(s%op, .false., 3, n, ks)
        r = 30_ik + 13_ik * n + 2_ik * s%nop + 3_ik * n * fsym_kernel_slots(ks)
        if (r > huge(lrw)) then
            info = FSYM_ERR_WORK_SIZE; msg = 'planets: RW would exceed a default integer'
            return
        end if
        lrw = int(r); liw = PL_IOP + 2 + s%nop
        info = FSYM_SUCCESS
    end subroutine pl_sizes

    !> Set up RW and IW for the method `label`, coordinates `icoord` (1 Jacobi, 2
    !> democratic, 3 Jacobi with the Kepler masses eta_k: PL_JACOBI_ETA), the central mass
    !> m0, the masses m(n) (massive first, then test particles of mass 0), G and the
    !> encounter radius `hill` in mutual Hill radii (0: off). Bad input or short arrays are
    !> refused and nothing is written.
    subroutine pl_setup(label, icoord, n, m0, m, g, hill, rw, lrw, iw, liw, info, msg)
        character(len=*), intent(in) :: label         !! method label
        integer, intent(in) :: icoord                 !! 1 Jacobi, 2 democratic, 3 (eta_k)
        integer, intent(in) :: n                      !! bodies besides the centre
        real(wp), intent(in) :: m0, m(n), g, hill     !! central mass, masses, G, Hill factor
        integer, intent(in) :: lrw, liw               !! lengths of rw and iw
        real(wp), intent(inout) :: rw(lrw)            !! real work array
        integer, intent(inout) :: iw(liw)             !! integer work array
        integer, intent(out) :: info                  !! status
        character(len=*), intent(inout) :: msg        !! message on error
        type(scheme_t) :: s
        type(kernel_state_t) :: ks
        type(planets_model_t) :: probe
        integer :: need_r, need_i, nop, k, ic, iu, iq, order, coords, km
        real(wp) :: xstar
        call pl_sizes(label, n, need_r, need_i, info, msg)
        if (info /= FSYM_SUCCESS) return
        if (lrw < need_r .or. liw < need_i) then
            info = FSYM_ERR_WORK_SIZE
            msg = 'planets: work arrays too short: need LRW = '//fsym_int_text(need_r)// &
                  ', LIW = '//fsym_int_text(need_i)//' (FSYMPW)'
            return
        end if
        if (.not. (hill >= 0.0_wp .and. hill <= huge(hill))) then
            info = FSYM_ERR_BAD_ARGUMENT; msg = 'planets: HILL must be finite and >= 0'
            return
        end if
        call coord_choice(icoord, coords, km)
        call probe%init(m0, m, g, coords, info, msg, hill, km)  ! checks m0, m, G, icoord
        if (info /= FSYM_SUCCESS) return
        call resolve_method(label, s, order, info, msg)
        nop = s%nop
        call fsym_kernel_layout(s%op, .false., 3, n, ks)
        call fsym_stability_interval(s, xstar)
        iw(1:need_i) = 0
        rw(1:need_r) = 0.0_wp
        iw(1) = PL_MAGIC; iw(2) = n; iw(3) = icoord; iw(4) = nop
        iw(5) = fsym_kernel_slots(ks); iw(6) = len_trim(label)
        do k = 1, len_trim(label)
            iw(12 + k) = iachar(label(k:k))
        end do
        iw(PL_IOP:PL_IOP + nop - 1) = s%op
        iw(PL_IOP + nop) = order
        iw(PL_IOP + nop + 2) = PL_GUARD
        call fsym_kernel_pack(ks, rw(1:KERNEL_NPACK))
        rw(19) = m0; rw(20) = g; rw(21) = hill; rw(22) = xstar
        rw(PL_RM:PL_RM + n - 1) = m
        ic = PL_RM + n; iu = ic + nop; iq = iu + nop + 1
        rw(ic:ic + nop - 1) = s%c
        rw(iu:iu + nop - 1) = s%u
        ! XL, VL not a number: the first call converts the caller's X, V
        rw(iq + 6 * n:iq + 12 * n - 1) = ieee_value(1.0_wp, ieee_quiet_nan)
        call seal(n, nop, rw, lrw, iw, liw)
        info = FSYM_SUCCESS
    end subroutine pl_setup

    !> FSYM_SUCCESS when RW and IW hold a set-up image for n bodies (checksum, guard word, not
    !> busy, lengths); else FSYM_ERR_NOT_INITIALIZED (not set up, or a word changed since),
    !> FSYM_ERR_SHAPE (another N), FSYM_ERR_WORK_SIZE (LRW or LIW short), FSYM_ERR_BUSY.
    pure integer function pl_check(n, rw, lrw, iw, liw) result(info)
        integer, intent(in) :: n, lrw, liw         !! bodies, lengths
        real(wp), intent(in) :: rw(lrw)            !! real work array
        integer, intent(in) :: iw(liw)             !! integer work array
        integer :: nop
        integer(ik) :: need
        info = FSYM_ERR_NOT_INITIALIZED
        if (liw < PL_IOP + 2) return
        if (iw(1) /= PL_MAGIC .or. iw(4) < 1 .or. iw(5) < 1 .or. iw(2) < 1) return
        nop = iw(4)
        info = FSYM_ERR_WORK_SIZE
        if (int(liw, ik) < PL_IOP + 2_ik + nop) return
        need = 30_ik + 13_ik * iw(2) + 2_ik * nop + 3_ik * iw(2) * iw(5)
        if (int(lrw, ik) < need) return
        info = FSYM_ERR_NOT_INITIALIZED
        if (iw(PL_IOP + nop + 2) /= PL_GUARD) return
        if (iw(PL_IOP + nop + 1) /= image_crc(iw(2), nop, rw, lrw, iw, liw)) return
        info = FSYM_ERR_BUSY
        if (iw(12) /= 0) return
        info = FSYM_ERR_SHAPE
        if (iw(2) /= n) return
        info = FSYM_SUCCESS
    end function pl_check

    !> NSTEP steps of size h from the heliocentric x, v (masses m0, m, G bitwise those of the
    !> set-up: otherwise FSYM_ERR_CHECKPOINT, the body in IW(9)). `extra`: the caller's force
    !> on the heliocentric positions; `frac` > 0: the step-size guard with limit frac x*.
    !> With a corrector, x, v (when not those of the last call) are mapped with the in-map,
    !> and the state handed back is the out-map of a copy of the mapped state.
    !> On failure x, v hold the state after the steps completed (IW(7)); unchanged when none
    !> was (a close encounter in the first step: FSYM_ERR_ENCOUNTER, the pair in IW(9:10)).
    subroutine pl_steps(n, m0, m, g, x, v, h, nstep, rw, lrw, iw, liw, info, msg, extra, frac)
        integer, intent(in) :: n                        !! bodies besides the centre
        real(wp), intent(in) :: m0, m(n), g             !! central mass, masses, G
        real(wp), intent(inout) :: x(3, n), v(3, n)     !! heliocentric state
        real(wp), intent(in) :: h                       !! step
        integer, intent(in) :: nstep                    !! steps to take
        integer, intent(in) :: lrw, liw                 !! lengths of rw and iw
        real(wp), intent(inout), target :: rw(lrw)      !! real work array
        integer, intent(inout) :: iw(liw)               !! integer work array
        integer, intent(out) :: info                    !! status
        character(len=*), intent(inout) :: msg          !! message on error
        class(force_model_t), intent(in), optional :: extra  !! caller's extra force
        real(wp), intent(in), optional :: frac          !! guard: fraction of x* (> 0: on)
        type(pl_model_t) :: sys
        type(kernel_state_t) :: ks
        type(guard_t) :: gd
        real(wp), pointer, contiguous :: q(:, :), vs(:, :), xl(:, :), vl(:, :), w(:)
        real(wp), allocatable :: xb(:, :), vb(:, :), qc(:, :), vc(:, :)
        integer :: nop, ic, iu, ih, iq, k, bad, order, coords, km, stm
        integer(ik) :: ndone
        logical :: give, take
        info = pl_check(n, rw, lrw, iw, liw)
        if (info /= FSYM_SUCCESS) then
            msg = 'planets: the work arrays are not a set-up image for these N (FSYMPI)'
            return                                  ! IW may be foreign: write nothing
        end if
        nop = iw(4); ic = PL_RM + n; iu = ic + nop; ih = iu + nop; iq = ih + 1
        order = iw(PL_IOP + nop)
        q(1:3, 1:n) => rw(iq:iq + 3 * n - 1)
        vs(1:3, 1:n) => rw(iq + 3 * n:iq + 6 * n - 1)
        xl(1:3, 1:n) => rw(iq + 6 * n:iq + 9 * n - 1)
        vl(1:3, 1:n) => rw(iq + 9 * n:iq + 12 * n - 1)
        w => rw(iq + 12 * n:iq + 12 * n + 3 * n * iw(5) - 1)
        iw(7:11) = 0
        ndone = 0
        bad = -2
        if (.not. same_bits(g, rw(20))) bad = -1
        if (.not. same_bits(m0, rw(19))) bad = 0
        do k = n, 1, -1
            if (.not. same_bits(m(k), rw(PL_RM + k - 1))) bad = k
        end do
        if (bad >= -1) then
            info = FSYM_ERR_CHECKPOINT; iw(9) = bad
        else if (nstep < 1) then
            info = FSYM_ERR_BAD_ARGUMENT
        else if (fsym_overlap(x, v)) then
            info = FSYM_ERR_BAD_ARGUMENT; iw(9) = -1
        else if (fsym_same(h, 0.0_wp) .or. .not. abs(h) <= huge(h)) then
            info = FSYM_ERR_BAD_STEP
        else if (.not. (all(abs(x) <= huge(x)) .and. all(abs(v) <= huge(v)))) then
            info = FSYM_ERR_NONFINITE_STATE      ! refused before the image takes it over
        end if
        if (info /= FSYM_SUCCESS) then
            call finish(); return
        end if
        call fsym_kernel_layout(iw(PL_IOP:PL_IOP + nop - 1), .false., 3, n, ks)
        call fsym_kernel_unpack(rw(1:KERNEL_NPACK), ks, info, msg)
        if (info /= FSYM_SUCCESS) then
            info = FSYM_ERR_NOT_INITIALIZED; call finish(); return
        end if
        call coord_choice(iw(3), coords, km)
        call sys%init(m0, m, g, coords, info, msg, rw(21), km)
        if (info /= FSYM_SUCCESS) then
            call finish(); return
        end if
        if (present(extra)) then
            allocate (sys%extra, source=extra)
            call fsym_kernel_invalidate(ks)     ! the caller's data may have changed
        end if
        if (any(iw(PL_IOP:PL_IOP + nop - 1) == OP_GRAD_KICK) .and. .not. sys%has_gradient()) then
            info = FSYM_ERR_NO_GRADIENT; call finish(); return
        end if
        allocate (xb(3, 0:n), vb(3, 0:n))
        take = .not. (all(same_bits(x, xl)) .and. all(same_bits(v, vl))) .or. &
               (order > 0 .and. .not. same_bits(h, rw(ih)))
        if (take) then                                              ! take_new
            call planets_helio_to_bary(n, sys%m, x, v, xb, vb)
            call sys%to_state(xb, vb, q, vs, rw(24:26), rw(27:29))
            xl = ieee_value(1.0_wp, ieee_quiet_nan); vl = xl         ! until it is mapped
        end if
        iw(12) = 1; call seal(n, nop, rw, lrw, iw, liw)   ! busy: the maps call UFORCE too
        if (take .and. order > 0) then                              ! the in-map
            rw(ih) = h
            call corrector(1, q, vs, info)
        end if
        if (take .and. info == FSYM_SUCCESS) then
            xl = x; vl = v
        end if
        if (info == FSYM_SUCCESS) then
            if (present(frac)) sys%guarded = frac > 0.0_wp
            if (sys%guarded) then
                allocate (sys%xi(3, 0:n))
                gd%on = .true.; gd%xstar = rw(22); gd%limit = min(frac, 1.0e6_wp) * rw(22)
                call fsym_guard_run(gd, nop, iw(PL_IOP:PL_IOP + nop - 1), rw(ic:ic + nop - 1), &
                                    rw(iu:iu + nop - 1), sys, ks, q, vs, w, h, int(nstep, ik), &
                                    ndone, info, .false.)
            else
                call fsym_kernel_run(nop, iw(PL_IOP:PL_IOP + nop - 1), rw(ic:ic + nop - 1), &
                                     rw(iu:iu + nop - 1), sys, ks, q, vs, w, h, &
                                     int(nstep, ik), ndone, info)
            end if
            call fsym_kernel_pack(ks, rw(1:KERNEL_NPACK))
        end if
        give = ndone > 0
        if (give) then                                             ! give_back
            allocate (qc(3, n), vc(3, n))
            qc = q; vc = vs
            if (order > 0) then                         ! the out-map, on the copy
                call corrector(-1, qc, vc, stm)
                if (stm /= FSYM_SUCCESS) then
                    info = stm; give = .false.
                end if
            end if
        end if
        iw(12) = 0
        if (info == FSYM_ERR_MODEL) then
            msg = ''
            call sys%failure(info, msg)
            if (info == FSYM_ERR_ENCOUNTER) then
                iw(9) = sys%encounter_i; iw(10) = sys%encounter_j
            end if
            if (sys%failed /= 0 .and. info == FSYM_ERR_MODEL) iw(11) = sys%kepler_body
        end if
        rw(23) = rw(23) + real(ndone, wp)
        if (give) then
            iw(7) = int(ndone)
            call sys%from_state(qc, vc, rw(24:26), rw(27:29), xb, vb)
            call planets_bary_to_helio(n, xb, vb, x, v)
            xl = x; vl = v
        else if (ndone > 0) then        ! the mapped state went on, x and v did not
            xl = ieee_value(1.0_wp, ieee_quiet_nan); vl = xl
        end if
        call finish()
    contains
        !> Keep the status in IW, seal it, and the message.
        subroutine finish()
            iw(8) = info
            call seal(n, nop, rw, lrw, iw, liw)
            if (info /= FSYM_SUCCESS) call pl_message(info, rw, lrw, iw, liw, msg)
        end subroutine finish
        !> The corrector's in-map (dir = 1) or out-map (dir = -1) of the state (y, u), with
        !> the step HM, as `processed_t` applies them (`fsym_processed_maps`).
        subroutine corrector(dir, y, u, st)
            integer, intent(in) :: dir
            real(wp), intent(inout) :: y(3, n), u(3, n)
            integer, intent(out) :: st
            integer :: opi(FSYM_MAP_MAX), opo(FSYM_MAP_MAX), nin, nout
            real(wp) :: ci(FSYM_MAP_MAX), ui(FSYM_MAP_MAX), co(FSYM_MAP_MAX), uo(FSYM_MAP_MAX)
            type(kernel_state_t) :: km
            real(wp), allocatable :: wm(:, :, :)
            integer(ik) :: nd
            call fsym_processed_maps(iw(PL_IOP:PL_IOP + nop - 1), rw(ic:ic + nop - 1), &
                                     rw(iu:iu + nop - 1), order, opi, ci, ui, nin, opo, co, &
                                     uo, nout)
            st = FSYM_SUCCESS
            if (dir > 0 .and. nin > 0) then
                call fsym_kernel_layout(opi(1:nin), .false., 3, n, km)
                allocate (wm(3, n, fsym_kernel_slots(km)))
                call fsym_kernel_run(nin, opi(1:nin), ci(1:nin), ui(1:nin), sys, km, y, u, wm, &
                                     rw(ih), 1_ik, nd, st)
            else if (dir < 0 .and. nout > 0) then
                call fsym_kernel_layout(opo(1:nout), .false., 3, n, km)
                allocate (wm(3, n, fsym_kernel_slots(km)))
                call fsym_kernel_run(nout, opo(1:nout), co(1:nout), uo(1:nout), sys, km, y, u, &
                                     wm, rw(ih), 1_ik, nd, st)
            end if
        end subroutine corrector
    end subroutine pl_steps

    !> The heliocentric state of the image (the X, V its last call returned; not a number
    !> before the first call): what a restart from RW and IW alone resumes bitwise.
    subroutine pl_state(n, x, v, rw, lrw, iw, liw, info)
        integer, intent(in) :: n                        !! bodies besides the centre
        real(wp), intent(out) :: x(3, n), v(3, n)       !! heliocentric state
        integer, intent(in) :: lrw, liw                 !! lengths of rw and iw
        real(wp), intent(in) :: rw(lrw)                 !! real work array
        integer, intent(in) :: iw(liw)                  !! integer work array
        integer, intent(out) :: info                    !! status
        integer :: iq
        info = pl_check(n, rw, lrw, iw, liw)
        if (info /= FSYM_SUCCESS) return
        iq = PL_RM + n + 2 * iw(4) + 1
        x = reshape(rw(iq + 6 * n:iq + 9 * n - 1), [3, n])
        v = reshape(rw(iq + 9 * n:iq + 12 * n - 1), [3, n])
    end subroutine pl_state

    !> The message of status `info` returned by the last call on the image: the pair of an
    !> encounter, the body whose mass differs, the steps completed; the status text alone
    !> when the image cannot be read or holds another status.
    subroutine pl_message(info, rw, lrw, iw, liw, msg)
        integer, intent(in) :: info                     !! the status returned
        integer, intent(in) :: lrw, liw                 !! lengths of rw and iw
        real(wp), intent(in) :: rw(lrw)                 !! real work array
        integer, intent(in) :: iw(liw)                  !! integer work array
        character(len=*), intent(inout) :: msg          !! the message
        character(len=PL_MSG_LEN) :: t
        integer :: chk
        chk = FSYM_ERR_NOT_INITIALIZED
        if (liw >= PL_IOP + 2) then
            if (iw(1) == PL_MAGIC) chk = pl_check(iw(2), rw, lrw, iw, liw)
        end if
        if (chk == FSYM_SUCCESS) then
            if (iw(8) /= info) chk = FSYM_ERR_NOT_INITIALIZED
        end if
        if (chk /= FSYM_SUCCESS .or. info == FSYM_SUCCESS) then
            call fsym_copy_printable(fsym_status_message(info), msg); return
        end if
        select case (info)
        case (FSYM_ERR_ENCOUNTER)
            t = 'bodies '//fsym_int_text(iw(9))//' and '//fsym_int_text(iw(10))// &
                ' within the Hill limit'
        case (FSYM_ERR_CHECKPOINT)
            if (iw(9) > 0) t = 'the mass of body '//fsym_int_text(iw(9))
            if (iw(9) == 0) t = 'the central mass'
            if (iw(9) == -1) t = 'G'
            t = trim(t)//' differs (bitwise) from the one of the work arrays: set up again '// &
                'to change masses'
        case (FSYM_ERR_MODEL)
            t = 'a force routine failed'
            if (iw(11) > 0) t = 'the Kepler solve of body '//fsym_int_text(iw(11))//' failed'
        case (FSYM_ERR_BAD_ARGUMENT)
            t = 'NSTEP < 1'
            if (iw(9) == -1) t = 'X and V share memory'
        case default
            t = 'planets step'
        end select
        t = trim(t)//'; '//fsym_int_text(iw(7))//' steps completed'
        if (iw(7) == 0) t = trim(t)//', X and V unchanged'
        if (iw(7) > 0) t = trim(t)//', X and V are the state after them'
        call fsym_copy_printable(fsym_status_message(info)//': '//trim(t), msg)
    end subroutine pl_message

    !> Total energy (kinetic + potential, barycentric) of a heliocentric state.
    subroutine pl_energy(n, m0, m, g, x, v, e)
        integer, intent(in) :: n                        !! bodies besides the centre
        real(wp), intent(in) :: m0, m(n), g             !! central mass, masses, G
        real(wp), intent(in) :: x(3, n), v(3, n)        !! heliocentric state
        real(wp), intent(out) :: e                      !! energy
        real(wp), allocatable :: xb(:, :), vb(:, :), mm(:)
        integer :: i, j
        allocate (xb(3, 0:n), vb(3, 0:n), mm(0:n))
        mm(0) = m0; mm(1:n) = m
        call planets_helio_to_bary(n, mm, x, v, xb, vb)
        e = 0.0_wp
        do i = 0, n
            e = e + 0.5_wp * mm(i) * sum(vb(:, i)**2)
        end do
        do i = 0, n
            do j = i + 1, n
                e = e - g * mm(i) * mm(j) / norm2(xb(:, j) - xb(:, i))
            end do
        end do
    end subroutine pl_energy

    ! ---- private -----------------------------------------------------------------------

    !> The model's coordinates and Kepler masses of ICOORD: 1 Jacobi (M_k = m0 eta_k /
    !> eta_(k-1)), 2 democratic heliocentric, 3 Jacobi with M_k = eta_k; others are passed on
    !> for `planets_init` to refuse.
    pure subroutine coord_choice(icoord, coords, km)
        integer, intent(in) :: icoord
        integer, intent(out) :: coords, km
        coords = icoord; km = PLANETS_KEPLER_WH
        if (icoord == PL_JACOBI_ETA) then
            coords = PLANETS_JACOBI; km = PLANETS_KEPLER_ETA
        end if
    end subroutine coord_choice

    !> Whether two reals have the same bits.
    elemental logical function same_bits(a, b)
        real(wp), intent(in) :: a, b
        same_bits = transfer(a, 0_int64) == transfer(b, 0_int64)
    end function same_bits

    !> Store the checksum of the image.
    pure subroutine seal(n, nop, rw, lrw, iw, liw)
        integer, intent(in) :: n, nop, lrw, liw
        real(wp), intent(in) :: rw(lrw)
        integer, intent(inout) :: iw(liw)
        iw(PL_IOP + nop + 1) = image_crc(n, nop, rw, lrw, iw, liw)
    end subroutine seal

    !> CRC-32 of IW (but its own word) and of the bits of RW(19:29 + N + 2 NOP): the
    !> parameters, the masses and the coefficients.
    pure integer function image_crc(n, nop, rw, lrw, iw, liw) result(c)
        integer, intent(in) :: n, nop, lrw, liw
        real(wp), intent(in) :: rw(lrw)
        integer, intent(in) :: iw(liw)
        integer(int64) :: table(0:255), crc, t
        integer :: j
        table = fsym_crc32_table()
        crc = CRC_ONES
        do j = 1, PL_IOP + nop + 2
            if (j == PL_IOP + nop + 1) cycle
            crc = fsym_crc32_feed(crc, int(iw(j), int64), 4, table)
        end do
        do j = 19, PL_RM + n + 2 * nop - 1
            if (j == 23) cycle                        ! the step count changes every call
            crc = fsym_crc32_feed(crc, transfer(rw(j), t), 8, table)
        end do
        crc = ieor(crc, CRC_ONES)
        if (crc > huge(c)) crc = crc - 4294967296_int64
        c = int(crc)
    end function image_crc

    !> The interaction's largest local frequency: 2 G (m_i + m_j) / r_ij^3 over the pairs of
    !> massive bodies and of test particles with massive bodies (inertial positions).
    subroutine pl_frequency(self, q, omega2, r, stat)
        class(pl_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out) :: omega2, r
        integer, intent(inout) :: stat
        real(wp) :: z(3), d2, w2
        integer :: i, j
        z = 0.0_wp
        if (self%coords == PLANETS_JACOBI) then
            call planets_jacobi_to_bary(self%n, self%m, self%eta, q, z, self%xi)
        else
            self%xi(:, 0) = 0.0_wp
            self%xi(:, 1:self%n) = q
        end if
        omega2 = 0.0_wp; r = 0.0_wp
        do i = 1, self%nm
            do j = i + 1, self%n
                d2 = sum((self%xi(:, j) - self%xi(:, i))**2)
                w2 = 2.0_wp * self%g * (self%m(i) + self%m(j)) / (d2 * sqrt(d2))
                if (.not. (w2 <= omega2)) then
                    omega2 = w2; r = sqrt(d2)
                end if
            end do
        end do
        associate (unused => stat); end associate
    end subroutine pl_frequency

    !> UFORCE at the heliocentric positions q (3, n).
    subroutine pl_f77_acceleration(self, q, a, stat)
        class(pl_f77_force_t), intent(inout) :: self  !! the wrapper
        real(wp), intent(in), contiguous :: q(:, :)   !! heliocentric positions
        real(wp), intent(out), contiguous :: a(:, :)  !! extra accelerations
        integer, intent(inout) :: stat                !! UFORCE's IERR
        call self%f(size(q, 2), q, a, self%rpar, self%ipar, stat)
    end subroutine pl_f77_acceleration

    logical function pl_has_frequency(self)
        class(pl_model_t), intent(in) :: self
        pl_has_frequency = self%guarded
    end function pl_has_frequency

end module fsym_legacy_planets
