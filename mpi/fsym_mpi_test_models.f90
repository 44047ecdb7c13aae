!> Test model of the MPI programs (fsym_mpi_driver, fsym_mpi_agree_check): the distributed
!> model with a rank that fails on purpose.
module fsym_mpi_driver_models
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_ERR_MODEL
    use fsym_mpi_nbody, only: mpi_nbody_model_t
    implicit none
    private

    !> `mpi_nbody_model_t` whose rank `fail_rank` reports a failure at its `fail_at`-th force
    !> evaluation (counting accelerations only).
    type, extends(mpi_nbody_model_t), public :: failing_model_t
        integer :: fail_rank = -1   !! the rank that fails
        integer :: fail_at = 0      !! at which of its force evaluations
        integer :: evals = 0        !! force evaluations so far
    contains
        procedure :: local_acceleration => failing_local_acceleration
    end type failing_model_t

contains

    !> The library's local force, except on the chosen rank at the chosen evaluation.
    subroutine failing_local_acceleration(self, qall, a, stat)
        class(failing_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in) :: qall(:, :)             !! positions of all bodies
        real(wp), intent(out) :: a(:, :)               !! own accelerations
        integer, intent(inout) :: stat                 !! set on the chosen evaluation
        self%evals = self%evals + 1
        call self%mpi_nbody_model_t%local_acceleration(qall, a, stat)
        if (self%rank == self%fail_rank .and. self%evals == self%fail_at) stat = FSYM_ERR_MODEL
    end subroutine failing_local_acceleration

end module fsym_mpi_driver_models
