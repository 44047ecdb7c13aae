!> Explicit interfaces of the F77 planetary drop-in (`fsym_legacy_planets_f77.f90`) and of
!> the N-body helpers FSYMNA, FSYMNG, FSYMGK, for Fortran 90+ callers that want their calls
!> checked (`use fsym_legacy_planets_api`). F77 callers need nothing.
module fsym_legacy_planets_api
    use fsym_kinds, only: wp
    use fsym_legacy_planets, only: fsym_pl_force
    use fsym_legacy_api, only: fsym_legacy_accel, fsym_legacy_grad
    implicit none
    private

    public :: FSYMPW, FSYMPI, FSYMPL, FSYMPU, FSYMP0, FSYMPX, FSYMPM, FSYMPE
    public :: FSYMNA, FSYMNG, FSYMGK, fsym_pl_force

    interface
        !> Work sizes of a method label for N bodies.
        subroutine FSYMPW(METHOD, N, LRW, LIW, INFO)
            implicit none
            character(len=*), intent(in) :: METHOD   !! method label
            integer, intent(in) :: N                 !! bodies besides the centre
            integer, intent(out) :: LRW, LIW, INFO   !! lengths, status
        end subroutine FSYMPW
        !> Set up the work arrays.
        subroutine FSYMPI(METHOD, ICOORD, N, M0, M, G, HILL, RW, LRW, IW, LIW, INFO)
            import :: wp
            implicit none
            character(len=*), intent(in) :: METHOD   !! method label
            integer, intent(in) :: ICOORD, N         !! coordinates, bodies
            real(wp), intent(in) :: M0, M(N), G      !! central mass, masses, G
            real(wp), intent(in) :: HILL             !! encounter radius (Hill radii)
            integer, intent(in) :: LRW, LIW          !! lengths
            real(wp), intent(inout) :: RW(LRW)       !! real work array
            integer, intent(inout) :: IW(LIW)        !! integer work array
            integer, intent(out) :: INFO             !! status
        end subroutine FSYMPI
        !> NSTEP steps of the heliocentric state.
        subroutine FSYMPL(N, M0, M, G, X, V, H, NSTEP, RW, LRW, IW, LIW, INFO)
            import :: wp
            implicit none
            integer, intent(in) :: N                 !! bodies besides the centre
            real(wp), intent(in) :: M0, M(N), G      !! central mass, masses, G
            real(wp), intent(inout) :: X(3, N), V(3, N)  !! heliocentric state
            real(wp), intent(in) :: H                !! step
            integer, intent(in) :: NSTEP, LRW, LIW   !! steps, lengths
            real(wp), intent(inout) :: RW(LRW)       !! real work array
            integer, intent(inout) :: IW(LIW)        !! integer work array
            integer, intent(out) :: INFO             !! status
        end subroutine FSYMPL
        !> FSYMPL with an extra force and the step-size guard.
        subroutine FSYMPU(N, M0, M, G, X, V, H, NSTEP, UFORCE, RPAR, LRPAR, IPAR, LIPAR, &
                          FRAC, RW, LRW, IW, LIW, INFO)
            import :: wp, fsym_pl_force
            implicit none
            integer, intent(in) :: N                 !! bodies besides the centre
            real(wp), intent(in) :: M0, M(N), G      !! central mass, masses, G
            real(wp), intent(inout) :: X(3, N), V(3, N)  !! heliocentric state
            real(wp), intent(in) :: H                !! step
            integer, intent(in) :: NSTEP             !! steps
            procedure(fsym_pl_force) :: UFORCE       !! extra force, or FSYMP0
            integer, intent(in) :: LRPAR, LIPAR      !! lengths of the caller's data
            real(wp), intent(inout), target :: RPAR(LRPAR)  !! the caller's real data
            integer, intent(inout), target :: IPAR(LIPAR)   !! the caller's integer data
            real(wp), intent(in) :: FRAC             !! guard (<= 0: off)
            integer, intent(in) :: LRW, LIW          !! lengths
            real(wp), intent(inout) :: RW(LRW)       !! real work array
            integer, intent(inout) :: IW(LIW)        !! integer work array
            integer, intent(out) :: INFO             !! status
        end subroutine FSYMPU
        !> The "no extra force" marker for FSYMPU.
        subroutine FSYMP0(N, XH, AH, RPAR, IPAR, IERR)
            import :: wp
            implicit none
            integer, intent(in) :: N                 !! bodies
            real(wp), intent(in) :: XH(3, N)         !! positions
            real(wp), intent(out) :: AH(3, N)        !! set to zero
            real(wp), intent(inout) :: RPAR(*)       !! not used
            integer, intent(inout) :: IPAR(*)        !! not used
            integer, intent(inout) :: IERR           !! not changed
        end subroutine FSYMP0
        !> The heliocentric state kept in the work arrays.
        subroutine FSYMPX(N, X, V, RW, LRW, IW, LIW, INFO)
            import :: wp
            implicit none
            integer, intent(in) :: N                 !! bodies
            real(wp), intent(out) :: X(3, N), V(3, N)  !! heliocentric state
            integer, intent(in) :: LRW, LIW          !! lengths
            real(wp), intent(in) :: RW(LRW)          !! real work array
            integer, intent(in) :: IW(LIW)           !! integer work array
            integer, intent(out) :: INFO             !! status
        end subroutine FSYMPX
        !> The message of a failed call.
        subroutine FSYMPM(INFO, RW, LRW, IW, LIW, MSG)
            import :: wp
            implicit none
            integer, intent(in) :: INFO, LRW, LIW    !! status, lengths
            real(wp), intent(in) :: RW(LRW)          !! real work array
            integer, intent(in) :: IW(LIW)           !! integer work array
            character(len=*), intent(out) :: MSG     !! the message
        end subroutine FSYMPM
        !> Total energy of a heliocentric state.
        subroutine FSYMPE(N, M0, M, G, X, V, E)
            import :: wp
            implicit none
            integer, intent(in) :: N                 !! bodies
            real(wp), intent(in) :: M0, M(N), G      !! central mass, masses, G
            real(wp), intent(in) :: X(3, N), V(3, N) !! heliocentric state
            real(wp), intent(out) :: E               !! energy
        end subroutine FSYMPE
        !> The library's N-body accelerations.
        subroutine FSYMNA(N, AM, G, EPS, X, A)
            import :: wp
            implicit none
            integer, intent(in) :: N                 !! bodies
            real(wp), intent(in) :: AM(N), G, EPS    !! masses, G, softening
            real(wp), intent(in) :: X(3, N)          !! positions
            real(wp), intent(out) :: A(3, N)         !! accelerations
        end subroutine FSYMNA
        !> The library's N-body gradient term.
        subroutine FSYMNG(N, AM, G, EPS, X, A, GT)
            import :: wp
            implicit none
            integer, intent(in) :: N                 !! bodies
            real(wp), intent(in) :: AM(N), G, EPS    !! masses, G, softening
            real(wp), intent(in) :: X(3, N), A(3, N) !! positions, accelerations
            real(wp), intent(out) :: GT(3, N)        !! gradient term
        end subroutine FSYMNG
        !> The gradient checker for ACCEL and GRAD routines.
        subroutine FSYMGK(ND, N, X, AM, ACCEL, GRAD, DELTA, WORST, IWHERE, INFO)
            import :: wp, fsym_legacy_accel, fsym_legacy_grad
            implicit none
            integer, intent(in) :: ND, N             !! dimensions, bodies
            real(wp), intent(in) :: X(ND, N), AM(N)  !! positions, masses
            procedure(fsym_legacy_accel) :: ACCEL    !! acceleration routine
            procedure(fsym_legacy_grad) :: GRAD      !! gradient routine
            real(wp), intent(in) :: DELTA            !! relative increment
            real(wp), intent(out) :: WORST           !! worst relative error
            integer, intent(out) :: IWHERE(2)        !! where
            integer, intent(out) :: INFO             !! status
        end subroutine FSYMGK
    end interface

end module fsym_legacy_planets_api
