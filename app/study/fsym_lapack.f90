!> Explicit interfaces for the LAPACK routines the analysis modules use, and nothing else.
!> Only `fsym_linear_stability` (a study module of app/) uses it.
module fsym_lapack
    use fsym_kinds, only: wp
    implicit none
    private

    public :: dgeev, dsyev

    interface
        !> Eigenvalues (and optionally eigenvectors) of a general real matrix.
        subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
            import :: wp
            implicit none
            character(len=1), intent(in) :: jobvl      !! 'N': no left eigenvectors
            character(len=1), intent(in) :: jobvr      !! 'N': no right eigenvectors
            integer, intent(in) :: n                   !! order of the matrix
            integer, intent(in) :: lda                 !! leading dimension of a
            real(wp), intent(inout) :: a(lda, *)       !! the matrix, overwritten
            real(wp), intent(out) :: wr(*)             !! real parts of the eigenvalues
            real(wp), intent(out) :: wi(*)             !! imaginary parts of the eigenvalues
            integer, intent(in) :: ldvl                !! leading dimension of vl
            real(wp), intent(inout) :: vl(ldvl, *)     !! left eigenvectors (unused with 'N')
            integer, intent(in) :: ldvr                !! leading dimension of vr
            real(wp), intent(inout) :: vr(ldvr, *)     !! right eigenvectors (unused with 'N')
            integer, intent(in) :: lwork               !! size of work; -1 = query
            real(wp), intent(inout) :: work(*)         !! workspace
            integer, intent(out) :: info               !! 0 on success
        end subroutine dgeev

        !> Eigenvalues (and optionally eigenvectors) of a real symmetric matrix.
        subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
            import :: wp
            implicit none
            character(len=1), intent(in) :: jobz       !! 'N': eigenvalues only
            character(len=1), intent(in) :: uplo       !! 'U' or 'L': triangle used
            integer, intent(in) :: n                   !! order of the matrix
            integer, intent(in) :: lda                 !! leading dimension of a
            real(wp), intent(inout) :: a(lda, *)       !! the matrix, overwritten
            real(wp), intent(out) :: w(*)              !! eigenvalues, ascending
            integer, intent(in) :: lwork               !! size of work; -1 = query
            real(wp), intent(inout) :: work(*)         !! workspace
            integer, intent(out) :: info               !! 0 on success
        end subroutine dsyev
    end interface

end module fsym_lapack
