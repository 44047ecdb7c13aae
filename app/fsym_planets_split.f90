!> A plain interpreter of a stage table with the model's own drift (`model%drift`), for the
!> Kepler-drift measurements (orders, the outer solar system) while the library's kernel
!> still does free flight at its drift stages. It takes the stages one by one, as the table
!> says (no first-same-as-last reuse: `evaluations_per_step` counts as the kernel would),
!> and stops at the first failure with the model's status. It is measurement code beside
!> the programs, not a second kernel: it keeps no cache, no undo and no counters.
module fsym_planets_split
    use fsym_kinds, only: wp, ik
    use fsym_force, only: force_model_t
    use fsym_scheme, only: scheme_t, OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK
    implicit none
    private

    public :: split_run, evaluations_per_step

contains

    !> Take `nsteps` steps of size h of `scheme` from (q, v); `a`, `g`, `qe` are work arrays
    !> of the state's shape. `stat` is the model's status of the first failure (0: none) and
    !> `ndone` the steps completed before it.
    subroutine split_run(scheme, model, q, v, h, nsteps, a, g, qe, stat, ndone)
        type(scheme_t), intent(in) :: scheme                !! stage table
        class(force_model_t), intent(inout) :: model        !! model with its drift
        real(wp), intent(inout), contiguous :: q(:, :)      !! positions
        real(wp), intent(inout), contiguous :: v(:, :)      !! velocities
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! steps to take
        real(wp), intent(inout), contiguous :: a(:, :), g(:, :), qe(:, :)  !! work
        integer, intent(out) :: stat                        !! model status (0: success)
        integer(ik), intent(out) :: ndone                   !! steps completed
        integer :: k
        real(wp) :: c, u
        stat = 0
        do ndone = 0, nsteps - 1
            do k = 1, scheme%nop
                c = scheme%c(k)
                u = scheme%u(k)
                select case (scheme%op(k))
                case (OP_DRIFT)
                    call model%drift(q, v, c * h, stat)
                case (OP_KICK)
                    call model%acceleration(q, a, stat)
                    if (stat == 0) v = v + (c * h) * a
                case (OP_GRAD_KICK)
                    call model%acceleration(q, a, stat)
                    if (stat == 0) call model%gradient(q, a, g, stat)
                    if (stat == 0) v = v + (c * h) * a + (u * h**3) * g
                case (OP_EXTRAP_KICK)
                    call model%acceleration(q, a, stat)
                    if (stat == 0) then
                        qe = q + (u * h * h) * a
                        call model%acceleration(qe, g, stat)
                    end if
                    if (stat == 0) v = v + (c * h) * g
                end select
                if (stat /= 0) return
            end do
        end do
        ndone = nsteps
    end subroutine split_run

    !> Force-equivalent evaluations per step, as the kernel counts them: forces with the
    !> first-same-as-last reuse plus gradients (a gradient counted as one).
    pure integer function evaluations_per_step(scheme)
        type(scheme_t), intent(in) :: scheme   !! stage table
        evaluations_per_step = scheme%nforce + scheme%ngrad
    end function evaluations_per_step

end module fsym_planets_split
