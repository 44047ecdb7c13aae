!> The state of the one splitting kernel (`fsym_kernel`): where each array lives in the
!> caller's work array, what the force cache holds, the step in progress and the counters;
!> and what is done to it outside a step: set up, the check of a call's entry state, forget
!> the cache, undo a suspended step.
!> Apart from the kernel so that a force model's own fused stepper (`force_model_t%advance`)
!> can advance it as the kernel would.
module fsym_kernel_state
    use fsym_kinds, only: wp, ik
    use fsym_scheme, only: OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK
    use fsym_kernel_loops, only: fsym_all_finite, fsym_loop_entry, fsym_loop_same, &
                                 fsym_loop_copy
    implicit none
    private

    public :: fsym_kernel_layout, fsym_kernel_invalidate, fsym_kernel_abort
    public :: fsym_kernel_entry, fsym_kernel_refused, fsym_kernel_last_drift, fsym_kernel_keep

    integer, parameter, public :: KERNEL_SUSPEND = -1  !! model stat / kernel stat: suspended
    integer, parameter, public :: REQ_NONE = 0           !! no force outstanding
    integer, parameter, public :: REQ_FORCE = 1          !! a(q) into slot `ia`
    integer, parameter, public :: REQ_GRADIENT = 2       !! g(q) into slot `ig` (a(q) in `ia`)
    integer, parameter, public :: REQ_FORCE_SHIFTED = 3  !! a(x) into `iae`, x in slot `iqe`

    !> The kernel's state: where each array lives in the work array, what the cache holds,
    !> the step in progress and the counters.
    type, public :: kernel_state_t
        integer :: d = 0, n = 0             !! dimensions, particles
        integer :: nslot = 0                !! slots of d*n reals in the work array
        integer :: ia = 1, ig = 1           !! slots: acceleration, gradient term at q
        integer :: iqe = 1, iae = 1         !! slots: shifted point, acceleration there
        integer :: iq0 = 1, iv0 = 1         !! slots: q, v at the start of the step
        integer :: iqlast = 1               !! slot: q the cached force belongs to (it and
                                            !! iq0 trade roles, see fsym_kernel_run)
        integer :: iqc = 1, ivc = 1         !! slots: compensation terms of q, v
        integer :: iqc0 = 1, ivc0 = 1       !! slots: compensation terms on entry
        integer :: klast = 0
            !! the last drift when a kick follows (`fsym_kernel_last_drift`; 0: q is stored
            !! as the cached force's point at the end of a call instead of by that drift)
        logical :: comp = .false.           !! Kahan-compensated updates
        logical :: have_a = .false., have_g = .false., have_x = .false.
            !! slots ia, ig, iae hold valid forces
        logical :: active = .false.         !! a suspended step is in progress
        logical :: qsaved = .false., vsaved = .false.
            !! the step in progress has saved q, v (slots iq0, iv0) at their first update
        integer :: pc = 0                   !! stage in progress, or that failed (0: on entry)
        integer :: req = REQ_NONE           !! force outstanding while suspended
        real(wp) :: h = 0.0_wp              !! step of the step in progress
        real(wp) :: xshift = 0.0_wp         !! u h^2 of the cached extrapolated force
        integer(ik) :: nf = 0, ng = 0       !! force and gradient evaluations accepted
    end type kernel_state_t

contains

    !> Set up `ks` for a scheme on arrays (d, n): the slots it needs (methods without
    !> gradient or extrapolation, and runs without compensation, pay no memory for them).
    !> The caller then provides `w(d, n, ks%nslot)`.
    pure subroutine fsym_kernel_layout(op, compensated, d, n, ks)
        integer, intent(in) :: op(:)                 !! the scheme's op codes
        logical, intent(in) :: compensated           !! Kahan-compensated updates
        integer, intent(in) :: d, n                  !! dimensions, particles
        type(kernel_state_t), intent(out) :: ks      !! the new state
        ks%d = d; ks%n = n; ks%comp = compensated; ks%klast = fsym_kernel_last_drift(op)
        ks%ia = 1; ks%iq0 = 2; ks%iv0 = 3; ks%iqlast = 4; ks%nslot = 4
        if (any(op == OP_GRAD_KICK)) then
            ks%ig = 5; ks%nslot = 5
        end if
        if (any(op == OP_EXTRAP_KICK)) then
            ks%iqe = ks%nslot + 1; ks%iae = ks%nslot + 2; ks%nslot = ks%nslot + 2
        end if
        if (compensated) then
            ks%iqc = ks%nslot + 1; ks%ivc = ks%nslot + 2; ks%iqc0 = ks%nslot + 3
            ks%ivc0 = ks%nslot + 4; ks%nslot = ks%nslot + 4
        end if
    end subroutine fsym_kernel_layout

    !> The check of the entry state of a kernel call (a new step) whose table does not start
    !> with a drift (a first drift is the check itself: q + s v is finite only if q and v
    !> are, s being finite): false when q or v is not finite (refused, the cache kept); the
    !> cache forgotten when q is not bitwise its point. `lazy`: no pass of its own, the
    !> first kick is the check (its forces are cached at q, q bitwise their point and so
    !> finite; v + s a finite only if v is); `fsym_kernel_refused` then decides.
    logical function fsym_kernel_entry(op1, ks, q, v, w, lazy) result(ok)
        integer, intent(in) :: op1                                   !! the first op code
        type(kernel_state_t), intent(inout) :: ks                    !! kernel state
        real(wp), intent(in) :: q(ks%d * ks%n), v(ks%d * ks%n)       !! state
        real(wp), intent(in) :: w(ks%d * ks%n, ks%nslot)             !! work array
        logical, intent(out) :: lazy                                 !! checked by the update
        logical :: moved
        ok = .true.
        lazy = .not. ks%comp .and. ks%have_a .and. &
               (op1 == OP_KICK .or. (op1 == OP_GRAD_KICK .and. ks%have_g))
        if (lazy) lazy = fsym_loop_same(size(q), q, w(:, ks%iqlast))
        if (lazy) return
        ok = fsym_loop_entry(size(q), q, v, w(:, ks%iqlast), ks%have_a, moved)
        if (ok .and. moved) call fsym_kernel_invalidate(ks)
    end function fsym_kernel_entry

    !> After the first update of a `lazy` call found a value that is not finite (q, v as
    !> saved without swap mode): true, refused on entry (`ks%pc` = 0; the update undone, the
    !> cache kept), when q or v was not finite on entry; false when the step overflowed.
    logical function fsym_kernel_refused(op1, ks, q, v, w) result(refused)
        integer, intent(in) :: op1                                   !! the first op code
        type(kernel_state_t), intent(inout) :: ks                    !! kernel state
        real(wp), intent(inout) :: q(ks%d * ks%n), v(ks%d * ks%n)    !! state
        real(wp), intent(in) :: w(ks%d * ks%n, ks%nslot)             !! work array
        integer :: i0
        i0 = merge(ks%iq0, ks%iv0, op1 == OP_DRIFT)      ! a drift updated q first, a kick v
        refused = .not. fsym_all_finite(size(q), w(:, i0))
        if (op1 == OP_DRIFT) refused = refused .or. .not. fsym_all_finite(size(v), v)
        if (.not. refused) return
        if (op1 == OP_DRIFT) call fsym_loop_copy(size(q), w(:, i0), q)
        if (op1 /= OP_DRIFT) call fsym_loop_copy(size(v), w(:, i0), v)
        ks%pc = 0
    end function fsym_kernel_refused

    !> The stage of the last drift of a table when a kick follows it (a force is then
    !> evaluated at the final q of a step), else 0.
    pure integer function fsym_kernel_last_drift(op) result(k)
        integer, intent(in) :: op(:)                                 !! op codes
        k = 0
        if (op(size(op)) == OP_DRIFT) return
        do k = size(op) - 1, 1, -1
            if (op(k) == OP_DRIFT) exit
        end do
    end function fsym_kernel_last_drift

    !> At the start of a compensated step: keep q, v and the compensation terms (slots iq0,
    !> iv0, iqc0, ivc0), the state the step restores on failure.
    pure subroutine fsym_kernel_keep(ks, q, v, w)
        type(kernel_state_t), intent(in) :: ks                   !! kernel state
        real(wp), intent(in) :: q(ks%d, ks%n), v(ks%d, ks%n)     !! state
        real(wp), intent(inout) :: w(ks%d, ks%n, ks%nslot)       !! work array
        w(:, :, ks%iq0) = q; w(:, :, ks%iv0) = v
        w(:, :, ks%iqc0) = w(:, :, ks%iqc); w(:, :, ks%ivc0) = w(:, :, ks%ivc)
    end subroutine fsym_kernel_keep

    !> Forget every cached force (after changing the model's parameters between steps).
    pure subroutine fsym_kernel_invalidate(ks)
        type(kernel_state_t), intent(inout) :: ks  !! kernel state
        ks%have_a = .false.; ks%have_g = .false.; ks%have_x = .false.
    end subroutine fsym_kernel_invalidate

    !> Undo a suspended step: restore q, v (and the compensation terms) as at its start
    !> (each saved by the step's first update of it).
    subroutine fsym_kernel_abort(ks, q, v, w)
        type(kernel_state_t), intent(inout) :: ks                !! kernel state
        real(wp), intent(inout) :: q(ks%d, ks%n), v(ks%d, ks%n)  !! state, restored
        real(wp), intent(inout) :: w(ks%d, ks%n, ks%nslot)       !! work array
        if (ks%active) then
            if (ks%qsaved) q = w(:, :, ks%iq0)
            if (ks%vsaved) v = w(:, :, ks%iv0)
            if (ks%comp) then
                w(:, :, ks%iqc) = w(:, :, ks%iqc0); w(:, :, ks%ivc) = w(:, :, ks%ivc0)
            end if
        end if
        call fsym_kernel_invalidate(ks)
        ks%active = .false.; ks%req = REQ_NONE
    end subroutine fsym_kernel_abort

end module fsym_kernel_state
