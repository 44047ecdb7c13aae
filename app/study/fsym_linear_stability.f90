!> Linear stability of any method, from its data.
!>
!> * For the harmonic oscillator, the 2x2 step map of any splitting scheme and its stability
!>   interval (0, x*) (module `fsym_oscillator`, re-exported here; it needs no LAPACK).
!> * For any linear force model, the one-step map of any stepper (including RKN) as a matrix,
!>   found by stepping the identity columns; its spectral radius by LAPACK `dgeev`; the
!>   model's frequencies by `dsyev`; and the largest stable step.
module fsym_linear_stability
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_SHAPE, FSYM_ERR_NONFINITE_STATE, FSYM_ERR_MODEL, &
                           FSYM_ERR_LAPACK, fsym_report, fsym_pass
    use fsym_scheme, only: scheme_t
    use fsym_force, only: force_model_t
    use fsym_stepper, only: stepper_t
    use fsym_methods, only: fsym_new_stepper
    use fsym_lapack, only: dgeev, dsyev
    use fsym_oscillator, only: fsym_oscillator_map, fsym_oscillator_trace, &
                               fsym_stability_interval
    implicit none
    private

    public :: fsym_oscillator_map, fsym_oscillator_trace, fsym_stability_interval
    public :: fsym_linear_step_map, fsym_spectral_radius, fsym_linear_frequencies
    public :: fsym_stable_step

contains

    !> One-step map (2dn x 2dn, ordering z = (q(:), v(:))) of the method `name` (any label of
    !> `fsym_new_stepper`, RKN included) for a LINEAR force model at step h: each column is
    !> one step of a fresh stepper from a unit vector, which is exact because the map is linear.
    subroutine fsym_linear_step_map(name, model, d, n, h, map, stat, errmsg)
        character(len=*), intent(in) :: name                  !! method label
        class(force_model_t), intent(inout) :: model          !! a linear force model
        integer, intent(in) :: d, n                           !! dimensions, particles
        real(wp), intent(in) :: h                             !! step
        real(wp), intent(out) :: map(:, :)                    !! (2dn, 2dn)
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        class(stepper_t), allocatable :: s
        real(wp), allocatable :: q(:, :), v(:, :)
        integer :: j, dn, st
        character(len=256) :: msg
        dn = d * n
        map = 0.0_wp
        if (d < 1 .or. n < 1 .or. size(map, 1) /= 2 * dn .or. size(map, 2) /= 2 * dn) then
            call fsym_report(FSYM_ERR_SHAPE, 'map must be (2dn, 2dn)', stat, errmsg); return
        end if
        allocate (q(d, n), v(d, n))
        do j = 1, 2 * dn
            call fsym_new_stepper(name, model, d, n, s, st, msg)
            if (st /= FSYM_SUCCESS) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
            q = 0.0_wp; v = 0.0_wp
            if (j <= dn) then
                q(1 + mod(j - 1, d), 1 + (j - 1) / d) = 1.0_wp
            else
                v(1 + mod(j - dn - 1, d), 1 + (j - dn - 1) / d) = 1.0_wp
            end if
            call s%step(model, q, v, h, st, msg)
            if (st /= FSYM_SUCCESS) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
            map(1:dn, j) = reshape(q, [dn])
            map(dn + 1:, j) = reshape(v, [dn])
        end do
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_linear_step_map

    !> Spectral radius max |lambda| of a square matrix (LAPACK dgeev; `map` is not changed).
    subroutine fsym_spectral_radius(map, rho, stat, errmsg)
        real(wp), intent(in) :: map(:, :)                     !! square matrix
        real(wp), intent(out) :: rho                          !! spectral radius
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        real(wp), allocatable :: a(:, :), wr(:), wi(:), work(:)
        real(wp) :: dummy(1, 1), query(1)
        integer :: n, info
        character(len=48) :: buf
        n = size(map, 1)
        rho = 0.0_wp
        if (size(map, 2) /= n .or. n < 1) then
            call fsym_report(FSYM_ERR_SHAPE, 'spectral radius of a non-square matrix', stat, &
                             errmsg)
            return
        end if
        if (.not. all(abs(map) <= huge(1.0_wp))) then
            call fsym_report(FSYM_ERR_NONFINITE_STATE, 'spectral radius of a non-finite matrix', &
                             stat, errmsg)
            return
        end if
        allocate (a, source=map)
        allocate (wr(n), wi(n))
        call dgeev('N', 'N', n, a, n, wr, wi, dummy, 1, dummy, 1, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dgeev('N', 'N', n, a, n, wr, wi, dummy, 1, dummy, 1, work, size(work), info)
        if (info /= 0) then
            write (buf, '(a,i0)') 'dgeev info = ', info
            call fsym_report(FSYM_ERR_LAPACK, trim(buf), stat, errmsg); return
        end if
        rho = maxval(hypot(wr, wi))
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_spectral_radius

    !> Angular frequencies of a linear force model a = -K q with K symmetric: sqrt of the
    !> eigenvalues of K (LAPACK dsyev), K found by evaluating a at the unit vectors.
    subroutine fsym_linear_frequencies(model, d, n, omega, stat, errmsg)
        class(force_model_t), intent(inout) :: model          !! a linear force model
        integer, intent(in) :: d, n                           !! dimensions, particles
        real(wp), intent(out) :: omega(:)                     !! (dn) frequencies, ascending
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        real(wp), allocatable :: kmat(:, :), q(:, :), a(:, :), work(:)
        real(wp) :: query(1)
        integer :: j, dn, mst, info
        character(len=48) :: buf
        dn = d * n
        omega = 0.0_wp
        if (d < 1 .or. n < 1 .or. size(omega) /= dn) then
            call fsym_report(FSYM_ERR_SHAPE, 'omega must have d*n entries', stat, errmsg)
            return
        end if
        allocate (kmat(dn, dn), q(d, n), a(d, n))
        do j = 1, dn
            q = 0.0_wp
            q(1 + mod(j - 1, d), 1 + (j - 1) / d) = 1.0_wp
            mst = 0
            call model%acceleration(q, a, mst)
            if (mst /= 0) then
                call fsym_report(FSYM_ERR_MODEL, 'linear frequencies', stat, errmsg); return
            end if
            kmat(:, j) = -reshape(a, [dn])
        end do
        call dsyev('N', 'U', dn, kmat, dn, omega, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dsyev('N', 'U', dn, kmat, dn, omega, work, size(work), info)
        if (info /= 0) then
            write (buf, '(a,i0)') 'dsyev info = ', info
            call fsym_report(FSYM_ERR_LAPACK, trim(buf), stat, errmsg); return
        end if
        omega = sqrt(max(omega, 0.0_wp))
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_linear_frequencies

    !> Largest step h* of the method `name` on a linear model such that the spectral radius of
    !> the one-step map stays <= 1 + tol on (0, h*]: a scan of `nscan` (default 400) equal
    !> steps up to `hmax`, then bisection (60 halvings). Returns hmax when no end is found.
    subroutine fsym_stable_step(name, model, d, n, hmax, hstar, stat, errmsg, tol, nscan)
        character(len=*), intent(in) :: name                  !! method label
        class(force_model_t), intent(inout) :: model          !! a linear force model
        integer, intent(in) :: d, n                           !! dimensions, particles
        real(wp), intent(in) :: hmax                          !! scan range
        real(wp), intent(out) :: hstar                        !! largest stable step
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        real(wp), intent(in), optional :: tol                 !! growth allowed (default 1e-6)
        integer, intent(in), optional :: nscan                !! scan points (default 400)
        real(wp) :: lo, hi, mid, grow
        integer :: k, ns, st
        logical :: ok
        character(len=256) :: msg
        grow = 1.0e-6_wp; ns = 400
        if (present(tol)) grow = tol
        if (present(nscan)) ns = max(1, nscan)
        hstar = hmax
        lo = 0.0_wp
        do k = 1, ns
            hi = hmax * k / ns
            call stable(hi, ok)
            if (st /= FSYM_SUCCESS) exit
            if (.not. ok) then
                do while (hi - lo > 4.0_wp * epsilon(1.0_wp) * hi)
                    mid = 0.5_wp * (lo + hi)
                    call stable(mid, ok)
                    if (st /= FSYM_SUCCESS) exit
                    if (ok) then
                        lo = mid
                    else
                        hi = mid
                    end if
                end do
                hstar = lo
                exit
            end if
            lo = hi
        end do
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        if (present(stat)) stat = FSYM_SUCCESS

    contains

        subroutine stable(h, is_stable)
            real(wp), intent(in) :: h
            logical, intent(out) :: is_stable
            real(wp) :: map(2 * d * n, 2 * d * n), rho
            call fsym_linear_step_map(name, model, d, n, h, map, st, msg)
            is_stable = .false.
            if (st /= FSYM_SUCCESS) return
            call fsym_spectral_radius(map, rho, st, msg)
            is_stable = st == FSYM_SUCCESS .and. rho <= 1.0_wp + grow
        end subroutine stable

    end subroutine fsym_stable_step

end module fsym_linear_stability
