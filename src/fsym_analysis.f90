!> Properties of a step map measured numerically: its Jacobian by finite differences, the
!> symplecticity defect max|M^T J M - J|, the reversibility defect, and order fits.
module fsym_analysis
    use fsym_kinds, only: wp, ik
    use fsym_status
    use fsym_force, only: force_model_t
    use fsym_stepper, only: stepper_t
    implicit none
    private

    public :: fsym_step_jacobian, fsym_symplectic_defect, fsym_reversibility_defect
    public :: fsym_order_fit, fsym_observed_orders

contains

    !> One-step Jacobian M (2dn x 2dn, ordering z = (q(:), v(:))) of `stepper` at (q, v),
    !> by the fourth-order central difference with relative increment `delta` (default 1e-3).
    !> The stepper is copied; the caller's is not advanced.
    subroutine fsym_step_jacobian(stepper, model, q, v, h, jac, stat, errmsg, delta)
        class(stepper_t), intent(in) :: stepper               !! method, initialised
        class(force_model_t), intent(inout) :: model          !! force model
        real(wp), intent(in) :: q(:, :), v(:, :)              !! base point
        real(wp), intent(in) :: h                             !! step
        real(wp), intent(out) :: jac(:, :)                    !! (2dn, 2dn)
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        real(wp), intent(in), optional :: delta               !! relative increment
        class(stepper_t), allocatable :: s
        real(wp), allocatable :: z0(:), zp(:, :), qq(:, :), vv(:, :)
        real(wp) :: del, dz
        integer :: m, dn, j, k, st
        integer, parameter :: off(4) = [-2, -1, 1, 2]
        real(wp), parameter :: wgt(4) = [1.0_wp, -8.0_wp, 8.0_wp, -1.0_wp] / 12.0_wp
        character(len=256) :: msg
        dn = size(q)
        m = 2 * dn
        if (size(jac, 1) /= m .or. size(jac, 2) /= m .or. any(shape(v) /= shape(q))) then
            call fsym_report(FSYM_ERR_SHAPE, 'jac must be (2dn, 2dn)', stat, errmsg); return
        end if
        del = 1.0e-3_wp
        if (present(delta)) del = delta
        allocate (z0(m), zp(m, 4), qq(size(q, 1), size(q, 2)), vv(size(q, 1), size(q, 2)))
        z0(1:dn) = reshape(q, [dn]); z0(dn + 1:) = reshape(v, [dn])
        do j = 1, m
            dz = del * max(1.0_wp, abs(z0(j)))
            do k = 1, 4
                zp(:, k) = z0
                zp(j, k) = z0(j) + off(k) * dz
                qq = reshape(zp(1:dn, k), shape(q)); vv = reshape(zp(dn + 1:, k), shape(q))
                allocate (s, source=stepper)
                call s%step(model, qq, vv, h, st, msg)
                deallocate (s)
                if (st /= FSYM_SUCCESS) then
                    call fsym_pass(st, msg, stat, errmsg); return
                end if
                zp(1:dn, k) = reshape(qq, [dn]); zp(dn + 1:, k) = reshape(vv, [dn])
            end do
            jac(:, j) = matmul(zp, wgt) / dz
        end do
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_step_jacobian

    !> max |M^T J M - J| for J = [[0, I], [-I, 0]] of size m = 2k.
    pure real(wp) function fsym_symplectic_defect(jac) result(defect)
        real(wp), intent(in) :: jac(:, :)   !! one-step Jacobian (m, m)
        real(wp), allocatable :: j0(:, :), r(:, :)
        integer :: m, k, i
        m = size(jac, 1); k = m / 2
        allocate (j0(m, m), r(m, m))
        j0 = 0.0_wp
        do i = 1, k
            j0(i, k + i) = 1.0_wp
            j0(k + i, i) = -1.0_wp
        end do
        r = matmul(transpose(jac), matmul(j0, jac)) - j0
        defect = maxval(abs(r))
    end function fsym_symplectic_defect

    !> Largest deviation after a step of h followed by a step of -h.
    subroutine fsym_reversibility_defect(stepper, model, q, v, h, defect, stat, errmsg)
        class(stepper_t), intent(in) :: stepper               !! method, initialised
        class(force_model_t), intent(inout) :: model          !! force model
        real(wp), intent(in) :: q(:, :), v(:, :)              !! start
        real(wp), intent(in) :: h                             !! step
        real(wp), intent(out) :: defect                       !! max |z(h, -h) - z|
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        class(stepper_t), allocatable :: s
        real(wp), allocatable :: qq(:, :), vv(:, :)
        integer :: st
        character(len=256) :: msg
        defect = huge(1.0_wp)
        allocate (s, source=stepper)
        qq = q; vv = v
        call s%step(model, qq, vv, h, st, msg)
        if (st == FSYM_SUCCESS) call s%step(model, qq, vv, -h, st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        defect = max(maxval(abs(qq - q)), maxval(abs(vv - v)))
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_reversibility_defect

    !> Least-squares slope of log(err) against log(h): the observed order.
    pure real(wp) function fsym_order_fit(h, err) result(p)
        real(wp), intent(in) :: h(:)     !! step sizes
        real(wp), intent(in) :: err(:)   !! errors at those steps (> 0)
        real(wp) :: x(size(h)), y(size(h)), xm, ym
        x = log(h); y = log(err)
        xm = sum(x) / size(x); ym = sum(y) / size(y)
        p = sum((x - xm) * (y - ym)) / sum((x - xm)**2)
    end function fsym_order_fit

    !> Orders between consecutive step sizes: log(err(i)/err(i+1)) / log(h(i)/h(i+1)).
    pure function fsym_observed_orders(h, err) result(p)
        real(wp), intent(in) :: h(:)     !! step sizes
        real(wp), intent(in) :: err(:)   !! errors
        real(wp) :: p(size(h) - 1)
        p = log(err(1:size(h) - 1) / err(2:)) / log(h(1:size(h) - 1) / h(2:))
    end function fsym_observed_orders

end module fsym_analysis
