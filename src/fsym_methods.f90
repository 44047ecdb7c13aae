!> Every method of the library by name: the splitting catalogue plus RKN, and a factory that
!> returns a ready stepper for a label.
module fsym_methods
    use fsym_kinds, only: wp
    use fsym_status
    use fsym_paper_schemes, only: fsym_catalogue, FSYM_NAME_LEN
    use fsym_force, only: force_model_t
    use fsym_stepper, only: stepper_t
    use fsym_integrator, only: integrator_t
    use fsym_rkn, only: rkn_t
    implicit none
    private

    public :: fsym_method_names, fsym_new_stepper

contains

    !> The paper's named splitting methods followed by `RKN`.
    pure function fsym_method_names() result(names)
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        names = [fsym_catalogue(), [character(len=FSYM_NAME_LEN) :: 'RKN']]
    end function fsym_method_names

    !> A stepper for the method `name` (any label `fsym_scheme_by_name` takes, or `RKN`), set
    !> up for arrays (d, n) and `model`. On error `stepper` is left as it was.
    subroutine fsym_new_stepper(name, model, d, n, stepper, stat, errmsg, extrapolate, &
                                compensated, t0)
        character(len=*), intent(in) :: name                  !! method label
        class(force_model_t), intent(in) :: model             !! force model
        integer, intent(in) :: d, n                           !! dimensions, particles
        class(stepper_t), allocatable, intent(inout) :: stepper  !! the new stepper
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        logical, intent(in), optional :: extrapolate          !! extrapolated gradient
        logical, intent(in), optional :: compensated          !! compensated summation
        real(wp), intent(in), optional :: t0                  !! start time
        type(integrator_t) :: split
        type(rkn_t) :: rkn
        integer :: st
        character(len=256) :: msg
        if (trim(adjustl(upper(name))) == 'RKN') then
            call rkn%init(d, n, st, msg, t0)
            if (st /= FSYM_SUCCESS) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
            if (allocated(stepper)) deallocate (stepper)
            allocate (stepper, source=rkn)
        else
            call split%init_by_name(name, model, d, n, st, msg, extrapolate, compensated, t0)
            if (st /= FSYM_SUCCESS) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
            if (allocated(stepper)) deallocate (stepper)
            allocate (stepper, source=split)
        end if
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_new_stepper

    pure function upper(s) result(r)
        character(len=*), intent(in) :: s
        character(len=len(s)) :: r
        integer :: k
        r = s
        do k = 1, len(s)
            if (s(k:k) >= 'a' .and. s(k:k) <= 'z') r(k:k) = achar(iachar(s(k:k)) - 32)
        end do
    end function upper

end module fsym_methods
