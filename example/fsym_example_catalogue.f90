!> Print the method catalogue as a Markdown table, every number read from the library:
!> stages, force and gradient evaluations per step, forward, symplectic, symmetric, order.
!> Run: fpm run --example fsym_example_catalogue
program fsym_example_catalogue
    use fsym
    implicit none
    character(len=FSYM_NAME_LEN), allocatable :: names(:)
    type(kepler_model_t) :: model             ! provides the gradient term, so every method fits
    class(stepper_t), allocatable :: stepper
    type(scheme_t) :: scheme
    integer :: i, stat
    character(len=256) :: errmsg
    character(len=16) :: nop, order, symmetric

    allocate (names, source=fsym_method_names())
    write (*, '(a)') '| method | stages | forces/step | gradients/step | forward | symplectic'// &
        ' | symmetric | order |'
    write (*, '(a)') '|---|---:|---:|---:|---|---|---|---:|'
    do i = 1, size(names)
        call fsym_new_stepper(trim(names(i)), model, 2, 1, stepper, stat, errmsg)
        if (stat /= FSYM_SUCCESS) then
            write (*, '(a)') trim(errmsg)
            error stop 1
        end if
        if (stepper%is_splitting()) then
            call fsym_scheme_by_name(trim(names(i)), scheme, stat, errmsg)
            if (stat /= FSYM_SUCCESS) then
                write (*, '(a)') trim(errmsg)
                error stop 1
            end if
            write (nop, '(i0)') scheme%nop
            write (order, '(i0)') scheme%order
            symmetric = yes_no(scheme%symmetric)
        else
            nop = '-'              ! RKN is not a splitting: no stage table
            order = '-'
            symmetric = '-'
        end if
        write (*, '(a,i0,a,i0,a)') '| '//trim(names(i))//' | '//trim(nop)//' | ', &
            stepper%forces_per_step(), ' | ', stepper%gradients_per_step(), ' | '// &
            yes_no(stepper%is_forward())//' | '//yes_no(stepper%is_symplectic())//' | '// &
            trim(symmetric)//' | '//trim(order)//' |'
    end do

contains

    !> 'yes' or 'no'.
    pure function yes_no(flag) result(s)
        logical, intent(in) :: flag  !! the flag
        character(len=:), allocatable :: s
        s = merge('yes', 'no ', flag)
        s = trim(s)
    end function yes_no

end program fsym_example_catalogue
