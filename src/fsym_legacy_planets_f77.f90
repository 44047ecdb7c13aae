!> F77-callable planetary drop-in (external subroutines, explicit-shape arrays, INTEGER
!> status INFO, caller's work arrays RW, IW; module `fsym_legacy_planets` holds the layout):
!>
!>     CALL FSYMPW(METHOD, N, LRW, LIW, INFO)          work sizes of a method label
!>     CALL FSYMPI(METHOD, ICOORD, N, M0, M, G, HILL, RW, LRW, IW, LIW, INFO)    set up
!>     CALL FSYMPL(N, M0, M, G, X, V, H, NSTEP, RW, LRW, IW, LIW, INFO)           steps
!>     CALL FSYMPU(N, M0, M, G, X, V, H, NSTEP, UFORCE, RPAR, LRPAR, IPAR, LIPAR, FRAC,
!>    &            RW, LRW, IW, LIW, INFO)      steps with an extra force and/or the guard
!>     CALL FSYMPX(N, X, V, RW, LRW, IW, LIW, INFO)    the state kept in RW (a restart)
!>     CALL FSYMPM(INFO, RW, LRW, IW, LIW, MSG)        the message of a failed call
!>     CALL FSYMPE(N, M0, M, G, X, V, E)               total energy of a heliocentric state
!>
!> and the built-in N-body force for a caller's own force routine: FSYMNA (accelerations),
!> FSYMNG (gradient term), FSYMGK (the gradient checker). See doc/legacy.md.

!> Work sizes of the method labelled METHOD for N bodies besides the centre:
!> LRW = 30 + 13 N + 2 NOP + 3 N NSLOT, LIW = 79 + NOP (doc/legacy.md lists NOP and NSLOT).
!> A corrected label (`WHK-L+C17`, `WH+C17`, `WHK-M+C17`, `T2+C5`: a kernel and a symplectic
!> corrector of order 3, 5, 7, 11 or 17) has the NOP and NSLOT of its kernel.
subroutine FSYMPW(METHOD, N, LRW, LIW, INFO)
    use fsym_legacy_planets, only: pl_sizes
    implicit none
    character(len=*), intent(in) :: METHOD   !! method label ('C''', 'A', 'T2', ...)
    integer, intent(in) :: N                 !! bodies besides the centre
    integer, intent(out) :: LRW, LIW         !! lengths needed
    integer, intent(out) :: INFO             !! status
    character(len=200) :: msg
    call pl_sizes(METHOD, N, LRW, LIW, INFO, msg)
end subroutine FSYMPW

!> Set up RW, IW for the method METHOD, coordinates ICOORD (1 Jacobi, 2 democratic
!> heliocentric, 3 Jacobi with the Kepler masses eta_k), central mass M0, masses M(N)
!> (massive bodies first, then test particles of mass 0), G, and the close-encounter radius
!> HILL in mutual Hill radii (0: no check). Bad input or short arrays: INFO /= 0 and nothing
!> written.
subroutine FSYMPI(METHOD, ICOORD, N, M0, M, G, HILL, RW, LRW, IW, LIW, INFO)
    use fsym_kinds, only: wp
    use fsym_legacy_planets, only: pl_setup
    implicit none
    character(len=*), intent(in) :: METHOD   !! method label
    integer, intent(in) :: ICOORD            !! 1 Jacobi, 2 democratic, 3 Jacobi (eta_k)
    integer, intent(in) :: N                 !! bodies besides the centre
    real(wp), intent(in) :: M0, M(N), G      !! central mass, masses, G
    real(wp), intent(in) :: HILL             !! encounter radius (mutual Hill radii; 0 off)
    integer, intent(in) :: LRW, LIW          !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)       !! real work array
    integer, intent(inout) :: IW(LIW)        !! integer work array
    integer, intent(out) :: INFO             !! status
    character(len=200) :: msg
    call pl_setup(METHOD, ICOORD, N, M0, M, G, HILL, RW, LRW, IW, LIW, INFO, msg)
end subroutine FSYMPI

!> NSTEP steps of size H of the heliocentric X(3,N), V(3,N). M0, M, G must be bitwise those
!> given to FSYMPI (INFO = 21 otherwise: set up again to change a mass). INFO = 25
!> (FSYM_ERR_ENCOUNTER): a close encounter, IW(9), IW(10) the pair; on any failure X, V hold
!> the state after the IW(7) steps completed (unchanged when IW(7) = 0). FSYMPM gives the
!> message.
subroutine FSYMPL(N, M0, M, G, X, V, H, NSTEP, RW, LRW, IW, LIW, INFO)
    use fsym_kinds, only: wp
    use fsym_legacy_planets, only: pl_steps
    implicit none
    integer, intent(in) :: N                 !! bodies besides the centre
    real(wp), intent(in) :: M0, M(N), G      !! central mass, masses, G
    real(wp), intent(inout) :: X(3, N)       !! heliocentric positions
    real(wp), intent(inout) :: V(3, N)       !! heliocentric velocities
    real(wp), intent(in) :: H                !! step
    integer, intent(in) :: NSTEP             !! steps
    integer, intent(in) :: LRW, LIW          !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)       !! work array set up by FSYMPI
    integer, intent(inout) :: IW(LIW)        !! work array set up by FSYMPI
    integer, intent(out) :: INFO             !! status
    character(len=200) :: msg
    call pl_steps(N, M0, M, G, X, V, H, NSTEP, RW, LRW, IW, LIW, INFO, msg)
end subroutine FSYMPL

!> FSYMPL with an extra force and the step-size guard. UFORCE(N, XH, AH, RPAR, IPAR, IERR)
!> adds accelerations AH(3,N) at the heliocentric positions XH (a J2, a post-Newtonian term,
!> a disk), with the caller's data RPAR(LRPAR), IPAR(LIPAR) (no COMMON needed); IERR /= 0
!> fails the step (INFO = 11). Pass FSYMP0 as UFORCE for none. With an extra force the
!> gradient methods (A, C, AN) are refused (INFO = 8): use A', C', AN'. FRAC > 0 turns the
!> guard on: a step where 2 G (m_i + m_j) / r_ij^3 of a pair of bodies puts h omega beyond
!> FRAC x* is refused (INFO = 20), as FSYMGD does; FRAC <= 0: no guard.
subroutine FSYMPU(N, M0, M, G, X, V, H, NSTEP, UFORCE, RPAR, LRPAR, IPAR, LIPAR, FRAC, &
                  RW, LRW, IW, LIW, INFO)
    use fsym_kinds, only: wp
    use fsym_legacy_planets, only: pl_steps, pl_f77_force_t, fsym_pl_force
    use fsym_legacy_planets_api, only: FSYMP0
    implicit none
    integer, intent(in) :: N                 !! bodies besides the centre
    real(wp), intent(in) :: M0, M(N), G      !! central mass, masses, G
    real(wp), intent(inout) :: X(3, N)       !! heliocentric positions
    real(wp), intent(inout) :: V(3, N)       !! heliocentric velocities
    real(wp), intent(in) :: H                !! step
    integer, intent(in) :: NSTEP             !! steps
    procedure(fsym_pl_force) :: UFORCE       !! extra force, or FSYMP0
    integer, intent(in) :: LRPAR, LIPAR      !! lengths of RPAR and IPAR (>= 1)
    real(wp), intent(inout), target :: RPAR(LRPAR)   !! the caller's real data
    integer, intent(inout), target :: IPAR(LIPAR)    !! the caller's integer data
    real(wp), intent(in) :: FRAC             !! guard: fraction of x* (<= 0: off)
    integer, intent(in) :: LRW, LIW          !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)       !! work array set up by FSYMPI
    integer, intent(inout) :: IW(LIW)        !! work array set up by FSYMPI
    integer, intent(out) :: INFO             !! status
    type(pl_f77_force_t) :: extra
    character(len=200) :: msg
    extra%f => UFORCE
    if (associated(extra%f, FSYMP0)) then
        call pl_steps(N, M0, M, G, X, V, H, NSTEP, RW, LRW, IW, LIW, INFO, msg, frac=FRAC)
    else
        extra%rpar => RPAR
        extra%ipar => IPAR
        call pl_steps(N, M0, M, G, X, V, H, NSTEP, RW, LRW, IW, LIW, INFO, msg, extra, FRAC)
    end if
end subroutine FSYMPU

!> The "no extra force" marker: pass it as UFORCE to FSYMPU. Never called by the library;
!> if called, it returns AH = 0.
subroutine FSYMP0(N, XH, AH, RPAR, IPAR, IERR)
    use fsym_kinds, only: wp
    implicit none
    integer, intent(in) :: N                 !! bodies
    real(wp), intent(in) :: XH(3, N)         !! positions
    real(wp), intent(out) :: AH(3, N)        !! set to zero
    real(wp), intent(inout) :: RPAR(*)       !! not used
    integer, intent(inout) :: IPAR(*)        !! not used
    integer, intent(inout) :: IERR           !! not changed
    associate (unused_x => XH, unused_r => RPAR(1), unused_i => IPAR(1), unused_e => IERR)
    end associate
    AH = 0.0_wp
end subroutine FSYMP0

!> The heliocentric X(3,N), V(3,N) kept in the work arrays: those the last FSYMPL/FSYMPU call
!> returned. After restoring RW and IW (a checkpoint is RW and IW, nothing else), this gives
!> the state to go on from; the run then continues bitwise as if never interrupted.
subroutine FSYMPX(N, X, V, RW, LRW, IW, LIW, INFO)
    use fsym_kinds, only: wp
    use fsym_legacy_planets, only: pl_state
    implicit none
    integer, intent(in) :: N                 !! bodies besides the centre
    real(wp), intent(out) :: X(3, N)         !! heliocentric positions
    real(wp), intent(out) :: V(3, N)         !! heliocentric velocities
    integer, intent(in) :: LRW, LIW          !! lengths of RW and IW
    real(wp), intent(in) :: RW(LRW)          !! work array
    integer, intent(in) :: IW(LIW)           !! work array
    integer, intent(out) :: INFO             !! status
    call pl_state(N, X, V, RW, LRW, IW, LIW, INFO)
end subroutine FSYMPX

!> The message of the status INFO that the last call on RW, IW returned (the pair of an
!> encounter, the body whose mass differs, the steps done), blank-padded or cut to MSG.
subroutine FSYMPM(INFO, RW, LRW, IW, LIW, MSG)
    use fsym_kinds, only: wp
    use fsym_legacy_planets, only: pl_message
    implicit none
    integer, intent(in) :: INFO              !! the status returned
    integer, intent(in) :: LRW, LIW          !! lengths of RW and IW
    real(wp), intent(in) :: RW(LRW)          !! work array
    integer, intent(in) :: IW(LIW)           !! work array
    character(len=*), intent(out) :: MSG     !! the message
    MSG = ''
    call pl_message(INFO, RW, LRW, IW, LIW, MSG)
end subroutine FSYMPM

!> Total energy E (kinetic + Newtonian potential, in the barycentric frame) of the
!> heliocentric state X(3,N), V(3,N) with central mass M0, masses M(N) and G.
subroutine FSYMPE(N, M0, M, G, X, V, E)
    use fsym_kinds, only: wp
    use fsym_legacy_planets, only: pl_energy
    implicit none
    integer, intent(in) :: N                 !! bodies besides the centre
    real(wp), intent(in) :: M0, M(N), G      !! central mass, masses, G
    real(wp), intent(in) :: X(3, N), V(3, N) !! heliocentric state
    real(wp), intent(out) :: E               !! energy
    call pl_energy(N, M0, M, G, X, V, E)
end subroutine FSYMPE

!> The library's N-body accelerations A(3,N) of N bodies of masses AM(N) at X(3,N) (G,
!> softening EPS), for a caller's own ACCEL routine (FSYMST, FSYMRC): bitwise those of
!> `nbody_model_t`.
subroutine FSYMNA(N, AM, G, EPS, X, A)
    use fsym_kinds, only: wp
    use fsym_nbody, only: fsym_nbody_accel
    implicit none
    integer, intent(in) :: N                 !! bodies
    real(wp), intent(in) :: AM(N), G, EPS    !! masses, G, softening length
    real(wp), intent(in) :: X(3, N)          !! positions
    real(wp), intent(out) :: A(3, N)         !! accelerations
    call fsym_nbody_accel(N, AM, G, EPS, X, A)
end subroutine FSYMNA

!> The library's N-body gradient term GT(3,N) (g_j = (1/m_j) d/dX_j sum_i m_i |A_i|^2) at
!> X given A = A(X), for a caller's own GRAD routine.
subroutine FSYMNG(N, AM, G, EPS, X, A, GT)
    use fsym_kinds, only: wp
    use fsym_nbody, only: fsym_nbody_gradient
    implicit none
    integer, intent(in) :: N                 !! bodies
    real(wp), intent(in) :: AM(N), G, EPS    !! masses, G, softening length
    real(wp), intent(in) :: X(3, N)          !! positions
    real(wp), intent(in) :: A(3, N)          !! accelerations at X
    real(wp), intent(out) :: GT(3, N)        !! gradient term
    call fsym_nbody_gradient(N, AM, G, EPS, X, A, GT)
end subroutine FSYMNG

!> The gradient checker for a caller's ACCEL and GRAD routines (those of FSYMST): compares
!> GRAD at X(ND,N) with central differences of sum_i AM_i |A_i|^2 (relative increment
!> DELTA, <= 0: 1e-5); WORST the largest relative error, at IWHERE = (component, body).
!> Typical values for a correct gradient: 1e-9..1e-7; a wrong factor or sign: 1e-2 or more.
subroutine FSYMGK(ND, N, X, AM, ACCEL, GRAD, DELTA, WORST, IWHERE, INFO)
    use fsym_kinds, only: wp
    use fsym_checks, only: fsym_check_gradient
    use fsym_legacy_api, only: fsym_legacy_accel, fsym_legacy_grad
    use fsym_legacy_work, only: legacy_model_t
    implicit none
    integer, intent(in) :: ND, N             !! dimensions, bodies
    real(wp), intent(in) :: X(ND, N)         !! positions
    real(wp), intent(in) :: AM(N)            !! masses
    procedure(fsym_legacy_accel) :: ACCEL    !! ACCEL(ND, N, X, A)
    procedure(fsym_legacy_grad) :: GRAD      !! GRAD(ND, N, X, A, G)
    real(wp), intent(in) :: DELTA            !! relative increment (<= 0: default)
    real(wp), intent(out) :: WORST           !! worst relative error
    integer, intent(out) :: IWHERE(2)        !! where (component, body)
    integer, intent(out) :: INFO             !! status
    type(legacy_model_t) :: model
    character(len=200) :: msg
    model%accel => ACCEL
    model%grad => GRAD
    if (DELTA > 0.0_wp) then
        call fsym_check_gradient(model, X, WORST, IWHERE, INFO, msg, AM, DELTA)
    else
        call fsym_check_gradient(model, X, WORST, IWHERE, INFO, msg, AM)
    end if
end subroutine FSYMGK
