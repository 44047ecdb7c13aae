!> Results of the outer-solar-system runs and their writer: an HDF5 file (through the shared
!> `fsym_h5` module), from which scripts/report_solar.py renders doc/solar-system.md.
module fsym_solar_output
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS
    use fsym_h5, only: h5_file_t, fsym_h5md_header, fsym_h5_safe_name
    implicit none
    private

    !> One row per (method, step).
    type, public :: solar_results_t
        character(len=4), allocatable :: methods(:)       !! method labels
        real(wp), allocatable :: h(:)                     !! steps (days)
        real(wp) :: t_end = 0.0_wp                        !! span (days)
        integer :: n = 0                                  !! bodies
        real(wp), allocatable :: err_phase(:, :)          !! |(q,v) - ref|_2 at t_end
        real(wp), allocatable :: err_q(:, :)              !! max_i |q_i - q_i^ref| (AU)
        real(wp), allocatable :: err_energy(:, :)         !! max over steps |E/E0 - 1|
        real(wp), allocatable :: seconds(:, :)            !! time spent in the steps
        integer(ik), allocatable :: nforce(:, :)          !! force evaluations
        integer(ik), allocatable :: ngrad(:, :)           !! gradient evaluations
        real(wp), allocatable :: q_end(:, :, :, :)        !! final positions (3, n, method, h)
        real(wp), allocatable :: v_end(:, :, :, :)        !! final velocities
        real(wp), allocatable :: q_ref(:, :), v_ref(:, :) !! reference state
    end type solar_results_t

    public :: write_solar_h5

contains

    !> The HDF5 file (through the shared `fsym_h5`): the H5MD header, attributes on `/`,
    !> `steps`, the `reference` state, and per method `methods/<safe name>/` (attribute
    !> `label`) the errors, counts, times and final states (3, n, steps) of each step.
    !> Written atomically: no partial file survives.
    subroutine write_solar_h5(path, data_path, res, version, stat, errmsg)
        character(len=*), intent(in) :: path                !! output file
        character(len=*), intent(in) :: data_path           !! the data file used
        character(len=*), intent(in) :: version             !! library version
        type(solar_results_t), intent(in) :: res            !! results
        integer, intent(out) :: stat                        !! status
        character(len=*), intent(inout) :: errmsg           !! message on error
        type(h5_file_t) :: f
        character(len=:), allocatable :: g
        integer :: km
        call f%create(path, stat, errmsg)
        if (stat /= FSYM_SUCCESS) return
        call fsym_h5md_header(f, 'fsym-solar', version, 'astronomical units: AU, days, '// &
                              'solar masses (G in AU^3 day^-2 per solar mass)', stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('/', 'description', 'outer solar system '// &
            '(Hairer, Lubich, Wanner), units AU, days, solar masses; program '// &
            'app/solar/fsym_solar.f90', &
            stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('/', 't_end', res%t_end, stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('parameters', 'data_file', data_path, stat, &
                                                  errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('parameters', 'methods', res%methods, stat, &
                                                  errmsg)
        if (stat == FSYM_SUCCESS) call f%set_attr('/', 'n_bodies', res%n, stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%write('steps', res%h, stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%write('reference/q', res%q_ref, stat, errmsg)
        if (stat == FSYM_SUCCESS) call f%write('reference/v', res%v_ref, stat, errmsg)
        do km = 1, size(res%methods)
            if (stat /= FSYM_SUCCESS) exit
            g = 'methods/'//fsym_h5_safe_name(res%methods(km))
            call f%set_attr(g, 'label', trim(res%methods(km)), stat, errmsg)
            g = g//'/'
            if (stat == FSYM_SUCCESS) then
              call f%write(g//'phase_space_error', res%err_phase(km, :), stat, errmsg)
            end if
            if (stat == FSYM_SUCCESS) then
              call f%write(g//'max_position_error', res%err_q(km, :), stat, errmsg)
            end if
            if (stat == FSYM_SUCCESS) then
              call f%write(g//'max_relative_energy_error', res%err_energy(km, :), stat, errmsg)
            end if
            if (stat == FSYM_SUCCESS) call f%write(g//'seconds', res%seconds(km, :), stat, errmsg)
            if (stat == FSYM_SUCCESS) then
              call f%write(g//'force_evaluations', res%nforce(km, :), stat, errmsg)
            end if
            if (stat == FSYM_SUCCESS) then
              call f%write(g//'gradient_evaluations', res%ngrad(km, :), stat, errmsg)
            end if
            if (stat == FSYM_SUCCESS) call f%write(g//'q_end', res%q_end(:, :, km, :), stat, errmsg)
            if (stat == FSYM_SUCCESS) call f%write(g//'v_end', res%v_end(:, :, km, :), stat, errmsg)
        end do
        if (stat /= FSYM_SUCCESS) then
            call f%abort()
            return
        end if
        call f%close(stat, errmsg)
    end subroutine write_solar_h5

end module fsym_solar_output
