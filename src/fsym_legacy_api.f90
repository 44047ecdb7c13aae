!> Explicit interfaces of the F77-callable entry points in `fsym_legacy.f90`, for Fortran 90+
!> callers that want their calls checked (`use fsym_legacy_api`). F77 callers need nothing.
module fsym_legacy_api
    use, intrinsic :: iso_fortran_env, only: int32
    use fsym_kinds, only: wp, ik
    implicit none
    private

    public :: FSYMID, FSYMWK, FSYMIN, FSYMST, FSYMRC, FSYMNF, FSYMMS, FSYMPK, FSYMUP
    public :: FSYMWL, FSYMIL, FSYMG0, FSYMNL, FSYMRS, FSYMCV, FSYMCL, FSYMCK, FSYMCR
    public :: FSYMGD, fsym_legacy_accel, fsym_legacy_grad, fsym_legacy_freq

    abstract interface
        !> The caller's acceleration routine: accelerations A of the bodies at positions X.
        subroutine fsym_legacy_accel(ND, N, X, A)
            import :: wp
            implicit none
            integer, intent(in) :: ND, N          !! dimensions, bodies
            real(wp), intent(in) :: X(ND, N)      !! positions
            real(wp), intent(out) :: A(ND, N)     !! accelerations
        end subroutine fsym_legacy_accel
        !> The caller's gradient-term routine: G at positions X, given the accelerations A.
        subroutine fsym_legacy_grad(ND, N, X, A, G)
            import :: wp
            implicit none
            integer, intent(in) :: ND, N                  !! dimensions, bodies
            real(wp), intent(in) :: X(ND, N), A(ND, N)    !! positions, accelerations
            real(wp), intent(out) :: G(ND, N)             !! gradient term
        end subroutine fsym_legacy_grad
        !> The caller's local-frequency routine (for the guard of FSYMGD): the largest
        !> omega^2 of its bodies or pairs at X (e.g. 2 G (m_i + m_j) / r_ij^3) and the
        !> distance R where it occurs.
        subroutine fsym_legacy_freq(ND, N, X, W2, R)
            import :: wp
            implicit none
            integer, intent(in) :: ND, N          !! dimensions, bodies
            real(wp), intent(in) :: X(ND, N)      !! positions
            real(wp), intent(out) :: W2           !! largest omega^2
            real(wp), intent(out) :: R            !! distance where it occurs
        end subroutine fsym_legacy_freq
    end interface

    interface
        !> Method id of a name (0 if unknown).
        subroutine FSYMID(NAME, METH)
            implicit none
            character(len=*), intent(in) :: NAME   !! method label
            integer, intent(out) :: METH           !! catalogue index
        end subroutine FSYMID
        !> Work-array lengths.
        subroutine FSYMWK(METH, ND, N, LRW, LIW, INFO)
            implicit none
            integer, intent(in) :: METH, ND, N     !! method id, dimensions, bodies
            integer, intent(out) :: LRW, LIW, INFO !! lengths, status
        end subroutine FSYMWK
        !> Set up the work arrays.
        subroutine FSYMIN(METH, ND, N, RW, LRW, IW, LIW, INFO)
            import :: wp
            implicit none
            integer, intent(in) :: METH, ND, N, LRW, LIW  !! method id, sizes
            real(wp), intent(inout) :: RW(LRW)            !! real work array
            integer, intent(inout) :: IW(LIW)             !! integer work array
            integer, intent(out) :: INFO                  !! status
        end subroutine FSYMIN
        !> NSTEP steps with the caller's acceleration (and gradient) routine.
        subroutine FSYMST(ND, N, X, V, H, NSTEP, ACCEL, GRAD, RW, LRW, IW, LIW, INFO)
            import :: wp, fsym_legacy_accel, fsym_legacy_grad
            implicit none
            integer, intent(in) :: ND, N                  !! dimensions, bodies
            real(wp), intent(inout) :: X(ND, N), V(ND, N) !! state
            real(wp), intent(in) :: H                     !! step
            integer, intent(in) :: NSTEP, LRW, LIW        !! steps, lengths
            real(wp), intent(inout) :: RW(LRW)            !! real work array
            integer, intent(inout) :: IW(LIW)             !! integer work array
            integer, intent(out) :: INFO                  !! status
            procedure(fsym_legacy_accel) :: ACCEL     !! acceleration routine
            procedure(fsym_legacy_grad) :: GRAD       !! gradient-term routine
        end subroutine FSYMST
        !> NSTEP guarded steps (the step-size guard of `set_guard`).
        subroutine FSYMGD(ND, N, X, V, H, NSTEP, ACCEL, GRAD, FREQ, FRAC, RW, LRW, IW, LIW, &
                          INFO)
            import :: wp, fsym_legacy_accel, fsym_legacy_grad, fsym_legacy_freq
            implicit none
            integer, intent(in) :: ND, N                  !! dimensions, bodies
            real(wp), intent(inout) :: X(ND, N), V(ND, N) !! state
            real(wp), intent(in) :: H                     !! step
            integer, intent(in) :: NSTEP, LRW, LIW        !! steps, lengths
            real(wp), intent(in) :: FRAC                  !! fraction of x* (<= 0: 1)
            real(wp), intent(inout) :: RW(LRW)            !! real work array
            integer, intent(inout) :: IW(LIW)             !! integer work array
            integer, intent(out) :: INFO                  !! status
            procedure(fsym_legacy_accel) :: ACCEL     !! acceleration routine
            procedure(fsym_legacy_grad) :: GRAD       !! gradient-term routine
            procedure(fsym_legacy_freq) :: FREQ       !! local-frequency routine
        end subroutine FSYMGD
        !> One step by reverse communication.
        subroutine FSYMRC(ND, N, X, V, H, RW, LRW, IW, LIW, IREQ, IPNT, INFO)
            import :: wp
            implicit none
            integer, intent(in) :: ND, N                  !! dimensions, bodies
            real(wp), intent(inout) :: X(ND, N), V(ND, N) !! state
            real(wp), intent(in) :: H                     !! step
            integer, intent(in) :: LRW, LIW               !! lengths
            real(wp), intent(inout) :: RW(LRW)            !! real work array
            integer, intent(inout) :: IW(LIW)             !! integer work array
            integer, intent(inout) :: IREQ                !! request
            integer, intent(out) :: IPNT(3)               !! pointers into RW
            integer, intent(out) :: INFO                  !! status
        end subroutine FSYMRC
        !> Evaluation counts.
        subroutine FSYMNF(RW, LRW, NF, NG)
            import :: wp
            implicit none
            integer, intent(in) :: LRW                    !! length of RW
            real(wp), intent(in) :: RW(LRW)               !! real work array
            integer, intent(out) :: NF, NG                !! counts
        end subroutine FSYMNF
        !> Status text.
        subroutine FSYMMS(INFO, MSG)
            implicit none
            integer, intent(in) :: INFO                   !! status code
            character(len=*), intent(out) :: MSG          !! its text
        end subroutine FSYMMS
        !> Work-array lengths for a method given by its label.
        subroutine FSYMWL(NAME, ND, N, LRW, LIW, INFO)
            implicit none
            character(len=*), intent(in) :: NAME   !! method label
            integer, intent(in) :: ND, N           !! dimensions, bodies
            integer, intent(out) :: LRW, LIW, INFO !! lengths, status
        end subroutine FSYMWL
        !> Set up the work arrays for a method given by its label.
        subroutine FSYMIL(NAME, ND, N, RW, LRW, IW, LIW, INFO)
            import :: wp
            implicit none
            character(len=*), intent(in) :: NAME          !! method label
            integer, intent(in) :: ND, N, LRW, LIW        !! sizes
            real(wp), intent(inout) :: RW(LRW)            !! real work array
            integer, intent(inout) :: IW(LIW)             !! integer work array
            integer, intent(out) :: INFO                  !! status
        end subroutine FSYMIL
        !> The "no gradient term" marker routine (pass as GRAD to FSYMST).
        subroutine FSYMG0(ND, N, X, A, G)
            import :: wp
            implicit none
            integer, intent(in) :: ND, N                  !! dimensions, bodies
            real(wp), intent(in) :: X(ND, N), A(ND, N)    !! positions, accelerations
            real(wp), intent(out) :: G(ND, N)             !! set to zero
        end subroutine FSYMG0
        !> Evaluation counts as 64-bit integers.
        subroutine FSYMNL(RW, LRW, NF, NG)
            import :: wp, ik
            implicit none
            integer, intent(in) :: LRW                    !! length of RW
            real(wp), intent(in) :: RW(LRW)               !! real work array
            integer(ik), intent(out) :: NF, NG            !! counts
        end subroutine FSYMNL
        !> Forget the cached force (after changing the model's parameters).
        subroutine FSYMRS(ND, N, X, V, RW, LRW, IW, LIW, INFO)
            import :: wp
            implicit none
            integer, intent(in) :: ND, N                  !! dimensions, bodies
            real(wp), intent(inout) :: X(ND, N), V(ND, N) !! state
            integer, intent(in) :: LRW, LIW               !! lengths
            real(wp), intent(inout) :: RW(LRW)            !! real work array
            integer, intent(inout) :: IW(LIW)             !! integer work array
            integer, intent(out) :: INFO                  !! status
        end subroutine FSYMRS
        !> Calling-convention check.
        subroutine FSYMCV(ICHK, X)
            import :: wp, int32
            implicit none
            integer(int32), intent(inout) :: ICHK(*)      !! (1, 2) on entry; verdict
            real(wp), intent(in) :: X                     !! 1.5D0
        end subroutine FSYMCV
        !> Checkpoint length.
        subroutine FSYMCL(ND, N, RW, LRW, IW, LIW, LCK, INFO)
            import :: wp
            implicit none
            integer, intent(in) :: ND, N, LRW, LIW        !! dimensions, bodies, lengths
            real(wp), intent(in) :: RW(LRW)               !! real work array
            integer, intent(in) :: IW(LIW)                !! integer work array
            integer, intent(out) :: LCK, INFO             !! checkpoint length, status
        end subroutine FSYMCL
        !> Write a checkpoint.
        subroutine FSYMCK(ND, N, X, V, RW, LRW, IW, LIW, CK, LCK, INFO)
            import :: wp
            implicit none
            integer, intent(in) :: ND, N, LRW, LIW, LCK   !! dimensions, bodies, lengths
            real(wp), intent(in) :: X(ND, N), V(ND, N)    !! state
            real(wp), intent(in) :: RW(LRW)               !! real work array
            integer, intent(in) :: IW(LIW)                !! integer work array
            real(wp), intent(out) :: CK(LCK)              !! the checkpoint
            integer, intent(out) :: INFO                  !! status
        end subroutine FSYMCK
        !> Restore from a checkpoint.
        subroutine FSYMCR(ND, N, X, V, RW, LRW, IW, LIW, CK, LCK, INFO)
            import :: wp
            implicit none
            integer, intent(in) :: ND, N, LRW, LIW, LCK   !! dimensions, bodies, lengths
            real(wp), intent(inout) :: X(ND, N), V(ND, N) !! state
            real(wp), intent(inout) :: RW(LRW)            !! real work array
            integer, intent(inout) :: IW(LIW)             !! integer work array
            real(wp), intent(in) :: CK(LCK)               !! the checkpoint
            integer, intent(out) :: INFO                  !! status
        end subroutine FSYMCR
        !> Pack XH, YH, ZH into X(3,N).
        subroutine FSYMPK(N, XH, YH, ZH, X)
            import :: wp
            implicit none
            integer, intent(in) :: N                      !! bodies
            real(wp), intent(in) :: XH(N), YH(N), ZH(N)   !! components
            real(wp), intent(out) :: X(3, N)              !! packed
        end subroutine FSYMPK
        !> Unpack X(3,N) into XH, YH, ZH.
        subroutine FSYMUP(N, X, XH, YH, ZH)
            import :: wp
            implicit none
            integer, intent(in) :: N                      !! bodies
            real(wp), intent(in) :: X(3, N)               !! packed
            real(wp), intent(out) :: XH(N), YH(N), ZH(N)  !! components
        end subroutine FSYMUP
    end interface

end module fsym_legacy_api
